#include "trivar/iga_petsc/petsc_session.hpp"

#include <sys/resource.h>

#include <climits>
#include <cstdio>
#include <new>

#include <slepcsys.h>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

bool active = false, started_once = false;

// The message of the PETSc error being raised: PETSc calls the handler where the error starts (INITIAL) and again
// in every PETSc caller it returns through (REPEAT); the first call says what went wrong.
std::string petsc_message;

PetscErrorCode record_error(MPI_Comm, int, const char* function, const char*, PetscErrorCode code, PetscErrorType type,
                            const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) petsc_message = std::string(function) + ": " + (message ? message : "");
  return code;
}

}  // namespace

PetscSession::PetscSession() {
  require(!started_once, "petsc: MPI can be started once per process");
  // PETSc's signal handlers would replace the ones trivar (output folders) and the sanitizers install.
  static char name[] = "trivar", no_handler[] = "-no_signal_handler";
  static char* args[] = {name, no_handler, nullptr};
  static char** argv = args;
  static int argc = 2;
  require(SlepcInitialize(&argc, &argv, nullptr, nullptr) == 0, "petsc: PETSc/SLEPc failed to start");
  started_once = active = true;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks_);
  // Instead of PETSc's traceback (many lines per rank): the message, kept for petsc_failure.
  PetscPushErrorHandler(record_error, nullptr);
}

PetscSession::~PetscSession() {
  PetscPopErrorHandler();
  SlepcFinalize();
  active = false;
}

bool petsc_session_active() { return active; }

std::vector<double> peak_memory_per_rank() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const double mine = static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux reports kilobytes
  int ranks = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  std::vector<double> all(static_cast<std::size_t>(ranks));
  MPI_Allgather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, PETSC_COMM_WORLD);
  return all;
}

namespace {

std::string broadcast_text(const std::string& text, int root) {
  unsigned long size = text.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, root, PETSC_COMM_WORLD);
  std::string out = text;
  out.resize(size);
  MPI_Bcast(out.data(), static_cast<int>(size), MPI_CHAR, root, PETSC_COMM_WORLD);
  return out;
}

}  // namespace

std::string broadcast_from_rank0(const std::string& text) { return broadcast_text(text, 0); }

void agree_on_failure(const std::exception_ptr& failure) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  int first = failure ? rank : INT_MAX;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (first == INT_MAX) return;
  std::string message;
  if (rank == first) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::bad_alloc&) {
      message = "out of memory on rank " + std::to_string(rank) + " (the request is larger than the memory available)";
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
      message = "rank " + std::to_string(rank) + " failed";
    }
  }
  message = broadcast_text(message, first);
  if (rank == first) std::rethrow_exception(failure);
  throw Error(message);
}

void petsc_failure(int code, const char* call) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  std::string message = std::string("petsc: ") + call + " failed";
  if (ranks > 1) message += " on rank " + std::to_string(rank);
  message += " (PETSc error " + std::to_string(code) + (petsc_message.empty() ? "" : ": " + petsc_message) + ")";
  petsc_message.clear();
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  if (ranks == 1) throw Error(message);
  std::fprintf(stderr, "trivar: error: %s\n", message.c_str());
  std::fflush(stderr);
  MPI_Abort(PETSC_COMM_WORLD, 1);
  throw Error(message);  // not reached: MPI_Abort ends every rank
}

double max_over_ranks(double x) {
  double m = x;
  MPI_Allreduce(&x, &m, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return m;
}

}  // namespace trivar
