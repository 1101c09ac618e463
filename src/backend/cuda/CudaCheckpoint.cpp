// CudaDynamics for checkpoint and restart (runtime/Backends.h): the travel at the snapshot of the
// set in use comes from the device, and a restored set goes on serving. upload() has already put
// the host's contact set (history included) on the device as the set in use; only the snapshot's
// travel, which upload() takes from the owners' travel now, is the restored one's.
#include "backend/cuda/CudaDynamics.h"

namespace deme::cuda {

bool CudaDynamics::travelAtSnapshot(std::vector<double>& travel) const {
    select();
    travel.resize(m_view.numOwners);
    if (!travel.empty()) m_baseline.downloadAsync(travel.data(), travel.size(), m_stream);
    synchronize(m_stream);
    return true;
}

bool CudaDynamics::resumeContactSet(const SimState& s, const std::vector<double>& travel) {
    if (travel.size() != s.owners.size() || m_numContacts != s.contacts.size()) return false;
    select();
    if (!travel.empty()) {
        m_baseline.uploadAsync(travel.data(), travel.size(), m_stream);
        m_orderBaseline.uploadAsync(travel.data(), travel.size(), m_stream);
    }
    synchronize(m_stream);  // (`travel` is the caller's: copied before it goes)
    return true;
}

}  // namespace deme::cuda
