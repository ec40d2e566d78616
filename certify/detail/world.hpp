// The processes one certification runs on: this process alone (World itself), or the ranks of an
// MPI job (world_mpi.cpp, built with -DDELCERT_MPI=ON; docs/design.md §4.11). The driver
// (certify.cpp) is the same program on every rank: the per-point loops of checks 3 and 7 are split
// between the ranks by a spatial partition, every rank's results are gathered on rank 0, and rank 0
// alone runs the global checks and writes the certificate. What crosses between ranks is bytes
// (certify/distributed.hpp encodes and decodes them); this class only moves them.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace delcert::certify::detail {

class World {
 public:
  virtual ~World() = default;
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  // How many ranks share this rank's machine (the default thread count divides its cores between them).
  virtual int ranks_on_this_machine() const { return 1; }
  // Rank 0: every rank's `mine`, in rank order (its own first). Other ranks: empty.
  virtual std::vector<std::string> gather(std::string mine) const { return {std::move(mine)}; }
  // Rank 0's `text`, on every rank.
  virtual std::string broadcast(std::string text) const { return text; }
  // Stops every rank after an internal error on this one (the others would wait for it forever).
  virtual void abort(int /*status*/) const {}
};

// The world delcert-certify runs in: an MPI job when started by mpirun and built with MPI, else
// this process alone. Defined by world_single.cpp or world_mpi.cpp (chosen by CMake).
std::unique_ptr<World> make_world(int& argc, char**& argv);

}  // namespace delcert::certify::detail
