#pragma once
// The process's MPI / PETSc / SLEPc run time. One session per process, alive while any distributed solve runs:
// it starts MPI (under mpirun: one process per rank) and PETSc with SLEPc, and finalises them when destroyed.
// Options for PETSc's own objects may be given in the environment variable PETSC_OPTIONS.
#include <exception>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace trivar {

class PetscSession {
public:
  // Throws trivar::Error when a session already ran in this process (MPI starts once) or PETSc fails to start.
  PetscSession();
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }

private:
  int rank_ = 0, ranks_ = 1;
};

// Whether a session is alive (the distributed solvers refuse to run without one).
bool petsc_session_active();

// The peak resident memory of every rank in bytes (getrusage), on every rank; collective.
std::vector<double> peak_memory_per_rank();

// Rank 0's text on every rank; collective.
std::string broadcast_from_rank0(const std::string& text);

// Every rank's verdict on a phase that may fail on some ranks only (their elements, their files): when
// `failure` is set on any rank, every rank throws, the lowest failing rank its own exception and the others
// trivar::Error with its message, so no rank is left waiting in a later collective call. Collective.
void agree_on_failure(const std::exception_ptr& failure);

// Runs `phase` on this rank and agrees on its outcome with the others (agree_on_failure); its result on
// success. Collective.
template <class Phase>
std::invoke_result_t<Phase> on_every_rank(Phase&& phase) {
  using Result = std::invoke_result_t<Phase>;
  std::exception_ptr failure;
  if constexpr (std::is_void_v<Result>) {
    try {
      phase();
    } catch (...) {
      failure = std::current_exception();
    }
    agree_on_failure(failure);
  } else {
    std::optional<Result> result;
    try {
      result.emplace(phase());
    } catch (...) {
      failure = std::current_exception();
    }
    agree_on_failure(failure);
    return std::move(*result);
  }
}

// A PETSc or SLEPc call `call` returned the error `code` on this rank. PETSc raises many errors on one rank only,
// while the others wait inside the same collective call, from which no message can free them: with several
// ranks this rank writes the one line "trivar: error: petsc: <call> failed on rank R (PETSc error N: <PETSc's
// message>)" to stderr and ends the job (MPI_Abort, exit status 1; mpiexec stops the other ranks, whose
// interrupt handlers remove their temporary files). On one rank it throws trivar::Error with that message.
[[noreturn]] void petsc_failure(int code, const char* call);

// The largest of every rank's x, on every rank; collective. Wall times of a distributed step are the slowest
// rank's.
double max_over_ranks(double x);

}  // namespace trivar
