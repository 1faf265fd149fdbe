#pragma once
// The processes a study runs on: MPI's ranks when it was started by mpirun (or srun), else just
// this one. MPI is initialised only then, so that a plain run neither needs nor touches it.
#include <string>
#include <vector>

namespace contact {

class Ranks {
 public:
  Ranks(int& argc, char**& argv);
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Every rank's string, in rank order, on rank 0; empty on the others.
  std::vector<std::string> gather(const std::string& mine) const;

 private:
  bool mpi_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace contact
