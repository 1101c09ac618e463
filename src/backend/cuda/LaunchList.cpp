#include "backend/cuda/LaunchList.h"

#include <deme/Error.h>

namespace deme::cuda {

void LaunchList::enqueue(Stream stream) const {
    std::vector<void*> argv;
    for (const Item& it : m_items) {
        argv.clear();
        for (size_t a = it.firstArg; a < it.firstArg + it.numArgs; a++)
            argv.push_back(const_cast<unsigned char*>(m_bytes.data()) + m_args[a].offset);
        argv.push_back(nullptr);
        launchKernel(*it.kernel, it.grid, it.block, it.sharedBytes, stream, argv.data(), m_overlap);
    }
}

}  // namespace deme::cuda
