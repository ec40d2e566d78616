// delcert-certify built without MPI (-DDELCERT_MPI=OFF, the default): this process alone.
#include "certify/detail/world.hpp"

namespace delcert::certify::detail {

std::unique_ptr<World> make_world(int&, char**&) { return std::make_unique<World>(); }

}  // namespace delcert::certify::detail
