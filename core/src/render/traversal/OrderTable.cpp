#include "octrace/render/OrderTable.h"

#include <algorithm>
#include <bit>
#include <vector>

namespace octrace {

OrderTable::OrderTable() {
    for (unsigned s = 0; s < 8; ++s) {
        for (unsigned byte = 0; byte < 256; ++byte) {
            std::vector<unsigned> kids;
            for (unsigned c = 0; c < 8; ++c)
                if (byte & (1u << c)) kids.push_back(c);
            std::sort(kids.begin(), kids.end(), [s](unsigned a, unsigned b) {
                return std::popcount(a ^ s) < std::popcount(b ^ s);
            });
            bool chain = kids.size() <= 4;
            for (std::size_t i = 1; chain && i < kids.size(); ++i) {
                unsigned prev = kids[i - 1] ^ s, cur = kids[i] ^ s;
                // Each step may only add bits (coordinates never go back), and must add some.
                chain = (prev & cur) == prev && prev != cur;
            }
            // A ray always leaves a box through its far faces, so it cannot stay in the child
            // at the box's near corner (c XOR s == 0) alone; the order of that one-child set
            // is still needed for state bytes masked by the node's non-empty children.
            producible_[s][byte] = chain && !kids.empty() && !(kids.size() == 1 && (kids[0] ^ s) == 0);
            if (!chain || kids.empty()) {
                table_[s][byte] = 0;
                continue;
            }
            Entry e = Entry(kids.size());
            for (std::size_t i = 0; i < kids.size(); ++i) e |= Entry(kids[i] << (3 + 3 * i));
            table_[s][byte] = e;
        }
    }
}

const OrderTable& OrderTable::instance() {
    static const OrderTable table;
    return table;
}

}  // namespace octrace
