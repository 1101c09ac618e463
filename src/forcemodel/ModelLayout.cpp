#include "forcemodel/ModelLayout.h"

#include <algorithm>

namespace deme {

std::string ModelLayout::description() const {
    switch (kind) {
        case DEMForceModel::Kind::FRICTIONAL_HERTZIAN:
            return "the frictional Hertzian model";
        case DEMForceModel::Kind::FRICTIONLESS_HERTZIAN:
            return "the frictionless Hertzian model";
        default:
            return "the custom force model";
    }
}

int indexOf(const std::vector<std::string>& list, const std::string& name) {
    const auto it = std::find(list.begin(), list.end(), name);
    return it == list.end() ? -1 : (int)(it - list.begin());
}

}  // namespace deme
