#include "processes.hpp"

namespace panelrad::cli {

namespace {
const Communicator* shared = nullptr;
}

const Communicator* shared_solve() { return shared; }

void set_shared_solve(const Communicator* communicator) {
  shared = communicator && communicator->size() > 1 ? communicator : nullptr;
}

bool writes_outputs() { return !shared || shared->rank() == 0; }

}  // namespace panelrad::cli
