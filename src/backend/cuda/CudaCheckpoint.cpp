// CudaDynamics for checkpoint and restart (runtime/Backends.h): the set in use can always go on
// serving. upload() has already put the host's contact set (history included) on the device as the
// set in use, and the owners' travel since its snapshot with the state: nothing more to restore.
#include "backend/cuda/CudaDynamics.h"

namespace deme::cuda {

bool CudaDynamics::contactSetResumable() const { return !m_setTrimmed; }

bool CudaDynamics::resumeContactSet(const SimState& s) {
    return s.owners.travel.size() == s.owners.size() && m_numContacts == s.contacts.size();
}

}  // namespace deme::cuda
