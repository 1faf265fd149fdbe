// run_distributed on a 4-ball chain whose output grid asks for more samples than the run may keep:
// rank 0's recorder refuses its first sample, a failure only rank 0 sees. Prints each rank's
// status and time reached; run under mpirun by test_chain_mpi, to see every rank return it instead
// of the other ranks waiting in their next collective for ever.
#include "contact_ode/models/ball_chain.hpp"
#include "distributed_penalty.hpp"

#include <mpi.h>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, code = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  try {
    const contact::BallChain chain(contact::BallChainParams{.n = 4});
    contact::SolveOptions span{.t_end = 0.05, .sample_dt = 0.005};
    span.limits.max_samples = 3;
    const contact::RunResult r = contact::run_distributed(chain, chain, {}, span, MPI_COMM_WORLD);
    std::printf("rank %d: %s at t = %g\n", rank, std::string(contact::to_string(r.status)).c_str(),
                r.t_reached);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    code = 1;
  }
  MPI_Finalize();
  return code;
}
