#include "runtime/HistoryPoolPolicy.h"

#include <cstdlib>
#include <string>

#include <deme/Error.h>

namespace deme {

HistoryPoolPolicy HistoryPoolPolicy::fromEnvironment() {
    HistoryPoolPolicy p;
    if (const char* m = std::getenv("DEME_POOLED_HISTORY")) {
        const std::string v = m;
        if (v == "auto" || v.empty())
            p.mode = Mode::AUTO;
        else if (v == "1")
            p.mode = Mode::ALWAYS;
        else if (v == "0")
            p.mode = Mode::NEVER;
        else
            throwError("Initialize", "DEME_POOLED_HISTORY is \"" + v + "\"; use auto, 1 or 0");
    }
    if (const char* m = std::getenv("DEME_HISTORY_POOL_SPARE")) {
        char* end = nullptr;
        const unsigned long long v = std::strtoull(m, &end, 10);
        if (!*m || *end || *m == '-' || *m == '+')
            throwError("Initialize", std::string("DEME_HISTORY_POOL_SPARE is \"") + m + "\"; use a number of slots");
        p.minSpare = (size_t)v;
    }
    return p;
}

}  // namespace deme
