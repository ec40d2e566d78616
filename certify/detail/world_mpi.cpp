// delcert-certify built with MPI (-DDELCERT_MPI=ON): the ranks of the job when started by mpirun or
// srun, else this process alone (no MPI_Init: a plain run needs no MPI runtime).
//
// Messages are sent in pieces of at most 2^30 bytes (MPI's counts are ints), after their length as
// a 64-bit integer; every receive names its source and tag, so the pieces of one message arrive in
// order (MPI's non-overtaking rule for one sender, one receiver and one tag).
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "certify/detail/world.hpp"

namespace delcert::certify::detail {
namespace {

constexpr std::size_t kPiece = std::size_t(1) << 30;
constexpr int kTag = 7;

class MpiWorld final : public World {
 public:
  MpiWorld(int& argc, char**& argv) {
    int provided = 0;  // only the main thread calls MPI; worker threads only compute
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
    MPI_Comm_size(local, &local_);
    MPI_Comm_free(&local);
  }
  ~MpiWorld() override { MPI_Finalize(); }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int ranks_on_this_machine() const override { return local_; }

  std::vector<std::string> gather(std::string mine) const override {
    if (rank_ != 0) {
      send(mine, 0);
      return {};
    }
    std::vector<std::string> all(size_);
    all[0] = std::move(mine);
    for (int r = 1; r < size_; ++r) all[r] = receive(r);
    return all;
  }

  std::string broadcast(std::string text) const override {
    std::uint64_t n = text.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    text.resize(n);
    for (std::size_t at = 0; at < n; at += kPiece)
      MPI_Bcast(text.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_CHAR, 0, MPI_COMM_WORLD);
    return text;
  }

  void abort(int status) const override {
    if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
  }

 private:
  static void send(const std::string& s, int to) {
    const std::uint64_t n = s.size();
    MPI_Send(&n, 1, MPI_UINT64_T, to, kTag, MPI_COMM_WORLD);
    for (std::size_t at = 0; at < n; at += kPiece)
      MPI_Send(s.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_CHAR, to, kTag, MPI_COMM_WORLD);
  }
  static std::string receive(int from) {
    std::uint64_t n = 0;
    MPI_Recv(&n, 1, MPI_UINT64_T, from, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string s(n, '\0');
    for (std::size_t at = 0; at < n; at += kPiece)
      MPI_Recv(s.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_CHAR, from, kTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
    return s;
  }
  int rank_ = 0, size_ = 1, local_ = 1;
};

// Set by Open MPI's mpirun, by PMIx launchers (Open MPI 5, Slurm's srun --mpi=pmix) and by
// PMI-1/2 launchers (MPICH's Hydra, srun --mpi=pmi2).
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace

std::unique_ptr<World> make_world(int& argc, char**& argv) {
  if (!launched_by_mpi()) return std::make_unique<World>();
  return std::make_unique<MpiWorld>(argc, argv);
}

}  // namespace delcert::certify::detail
