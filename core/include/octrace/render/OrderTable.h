#pragma once
/// @file OrderTable.h
/// The 8 x 256 child order table of paper A (section 4): for each sign pattern of the ray
/// direction and each state byte (set of children a ray crosses inside a box), the order in
/// which the ray visits those children.
///
/// Child index c = 4*x + 2*y + z. The sign pattern s has bit 2 set when the direction's x
/// component is negative, bit 1 for y, bit 0 for z. Moving along the ray, every coordinate
/// changes monotonically, so the crossed children form a chain under inclusion of the bits of
/// (c XOR s); the order is by popcount(c XOR s). A byte whose children do not form such a
/// chain cannot be produced by any ray: the table marks it invalid (count 0). Nor can the
/// near-corner child alone (c XOR s == 0: a ray leaves every box through its far faces);
/// its entry still gives the order (it arises after masking with a node's non-empty
/// children) but producible() says no. The traversal never produces a non-producible byte.
#include <array>
#include <cstdint>

namespace octrace {

class OrderTable {
public:
    /// Packed entry: bits 0-2 count (0..4), then 3 bits per child in visiting order.
    using Entry = std::uint16_t;

    static const OrderTable& instance();

    Entry entry(unsigned sign, unsigned stateByte) const { return table_[sign][stateByte]; }
    static int count(Entry e) { return e & 7; }
    static int child(Entry e, int i) { return (e >> (3 + 3 * i)) & 7; }
    /// True when some ray can cross exactly this set of children (empty set included).
    bool producible(unsigned sign, unsigned stateByte) const { return stateByte == 0 || producible_[sign][stateByte]; }

private:
    OrderTable();
    std::array<std::array<Entry, 256>, 8> table_{};
    std::array<std::array<bool, 256>, 8> producible_{};
};

}  // namespace octrace
