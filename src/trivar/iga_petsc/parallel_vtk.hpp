#pragma once
// Parallel VTK output of a distributed solution: every rank writes the elements it assembled (its slab of each
// patch, ElementPartition, or its run of a locally refined space's elements) as `<stem>_<rank>.vtu`
// (io/vtk_writer.hpp, io/lr_vtk.hpp: Bezier cells), and rank 0 writes `<stem>.pvtu`, the index ParaView opens to
// load all pieces. The folder must be the same on every rank (a shared file system, as MPI-IO output assumes).
// Collective: a file one rank cannot write makes every rank throw (petsc_session.hpp, agree_on_failure).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

struct ParallelField {
  std::string name;
  Eigen::VectorXd coefs;  // every dof, component-major over the global basis
  int components = 1;
};

// The piece file names of a stem for `ranks` ranks, in rank order (what the caller reserves in its folder).
std::vector<std::string> parallel_vtu_files(const std::string& stem, int ranks);

template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem,
                        const MultipatchSpace<D>& space, const std::vector<ParallelField>& fields);

// A locally refined space (LR, HB, THB; refined_space.hpp) with the geometry it was built from: every rank writes
// the contiguous run of the element list it assembled (rank_partition), one Bezier cell per element with the
// fields' exact Bezier coefficients, as the serial output of refined geometries (io/lr_vtk.hpp). Throws
// trivar::Error (every rank) when the geometry's elements are not the space's.
template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const LRSpline<D>& geometry, const std::vector<ParallelField>& fields);
template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const HierarchicalSpline<D>& geometry, const std::vector<ParallelField>& fields);
// A multi-block space (RefinedSpace::blocks, fit/multiblock_space.hpp: the blocks' elements one block after the
// other, each in its LR order) with its blocks: every rank writes its run of the element list as one piece per
// block the run meets (that block's part of the run), as the serial multi-block output writes one piece per block.
// Throws trivar::Error (every rank) when the blocks' elements are not the space's.
template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const std::vector<LRSpline<D>>& blocks, const std::vector<ParallelField>& fields);

}  // namespace trivar
