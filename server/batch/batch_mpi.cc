// MPI side of `hybridsim batch --mpi`: a BatchComm over MPI_COMM_WORLD. Compiled only when
// CMake finds MPI (HYBRIDSIM_BATCH_MPI); otherwise make_mpi_comm() says how to get it.
#include "server/batch/batch.h"

#ifdef HYBRIDSIM_BATCH_MPI
#include <mpi.h>
#endif

#include <stdexcept>

namespace server {

#ifdef HYBRIDSIM_BATCH_MPI

namespace {

class MpiComm : public BatchComm {
 public:
  MpiComm() {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      // Single-threaded use: the ranks only start worker processes (fork/exec) and wait.
      // The workers, not the ranks, enter private network namespaces.
      if (MPI_Init(nullptr, nullptr) != MPI_SUCCESS) throw std::runtime_error("MPI_Init failed");
      owner_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiComm() override {
    if (owner_) MPI_Finalize();
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  bool all(bool ok) override {
    int mine = ok ? 1 : 0, every = 0;
    MPI_Allreduce(&mine, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return every == 1;
  }
  std::vector<std::string> gather(const std::string& text) override {
    const int len = static_cast<int>(text.size());
    std::vector<int> lens(rank_ == 0 ? size_ : 0), offsets(rank_ == 0 ? size_ : 0);
    MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<char> all;
    if (rank_ == 0) {
      int total = 0;
      for (int r = 0; r < size_; ++r) {
        offsets[r] = total;
        total += lens[r];
      }
      all.resize(static_cast<std::size_t>(total) + 1);
    }
    MPI_Gatherv(text.data(), len, MPI_CHAR, all.data(), lens.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
    std::vector<std::string> out;
    if (rank_ == 0)
      for (int r = 0; r < size_; ++r) out.emplace_back(all.data() + offsets[r], static_cast<std::size_t>(lens[r]));
    return out;
  }

 private:
  int rank_ = 0, size_ = 1;
  bool owner_ = false;
};

}  // namespace

std::unique_ptr<BatchComm> make_mpi_comm() { return std::make_unique<MpiComm>(); }
bool batch_has_mpi() { return true; }

#else

std::unique_ptr<BatchComm> make_mpi_comm() {
  throw std::runtime_error("--mpi: this hybridsim was built without MPI (install an MPI, e.g. Debian's "
                           "libopenmpi-dev, and re-run cmake)");
}
bool batch_has_mpi() { return false; }

#endif

}  // namespace server
