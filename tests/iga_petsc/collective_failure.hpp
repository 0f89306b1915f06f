#pragma once
// A PETSc error raised inside a collective call on one rank only, for tests/iga_petsc/collective_failure_test.py:
// every rank inserts into a matrix preallocated for its diagonal only, the last rank also one entry of a row
// the first rank owns, outside that row's preallocation. The entry travels at MatAssemblyEnd and the first rank
// alone fails inserting it, while the others continue into the call's later collective steps. The job must end
// with the one error line of that rank, not hang. Returns only when no error was raised.
int fail_inside_a_collective_call();
