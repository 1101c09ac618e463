#include "runtime/HistoryPoolPolicy.h"

#include <cstdlib>
#include <string>

#include <deme/Error.h>

#include "runtime/EnvironmentCount.h"

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
    environmentCount("DEME_HISTORY_POOL_SPARE", "Initialize", "a number of slots", p.minSpare);
    return p;
}

}  // namespace deme
