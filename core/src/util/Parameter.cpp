#include "octrace/util/Parameter.h"

#include <cctype>

namespace octrace {

std::string sayParameters(std::string_view text, const std::function<std::optional<std::string>(std::string_view key)>& say) {
    std::string out;
    out.reserve(text.size());
    std::size_t i = 0;
    while (i < text.size()) {
        const std::size_t open = text.find('`', i);
        if (open == std::string_view::npos) break;
        const std::size_t close = text.find('`', open + 1);
        if (close == std::string_view::npos) break;
        const std::string_view key = text.substr(open + 1, close - open - 1);
        bool isKey = !key.empty();
        for (char c : key) isKey = isKey && (std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_');
        out.append(text.substr(i, open - i));
        const std::optional<std::string> word = isKey && say ? say(key) : std::nullopt;
        if (word) {
            out += *word;
            i = close + 1;
        } else {
            out += '`';  // not a parameter: keep it, and look for one from the next backtick on
            i = open + 1;
        }
    }
    out.append(text.substr(i));
    return out;
}

}  // namespace octrace
