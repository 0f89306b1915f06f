#include "trivar/iga_petsc/parallel_vtk.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <type_traits>
#include <regex>
#include <sstream>

#include <mpi.h>
#include <petscsys.h>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/refined_field.hpp"
#include "trivar/iga/solution_field.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"
#include "trivar/io/lr_vtk.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

std::vector<std::string> parallel_vtu_files(const std::string& stem, int ranks) {
  std::vector<std::string> names{stem + ".pvtu"};
  for (int r = 0; r < ranks; ++r) names.push_back(stem + "_" + std::to_string(r) + ".vtu");
  return names;
}

namespace {

// The .pvtu index: the arrays of the first piece's header (written by io::write_vtu) declared once, then the
// pieces. The header is text up to the appended binary section.
std::string pvtu_index(const std::filesystem::path& first_piece, const std::vector<std::string>& pieces) {
  std::ifstream in(first_piece, std::ios::binary);
  std::string header, line;
  while (std::getline(in, line) && line.find("<AppendedData") == std::string::npos) header += line + "\n";
  const std::regex section(R"(<(PointData|CellData|Points)([^>]*)>([\s\S]*?)</\1>)");
  const std::regex array(R"re(<DataArray type="([^"]+)"(?: Name="([^"]*)")?(?: NumberOfComponents="(\d+)")?)re");
  std::ostringstream os;
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"2.1\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n";
  const std::string piece = header.substr(0, header.find("</Piece>"));
  for (std::sregex_iterator s(piece.begin(), piece.end(), section), end; s != end; ++s) {
    const std::string body = (*s)[3];
    os << "    <P" << (*s)[1] << (*s)[2] << ">\n";
    for (std::sregex_iterator a(body.begin(), body.end(), array); a != end; ++a) {
      os << "      <PDataArray type=\"" << (*a)[1] << "\"";
      if ((*a)[2].matched) os << " Name=\"" << (*a)[2] << "\"";
      if ((*a)[3].matched) os << " NumberOfComponents=\"" << (*a)[3] << "\"";
      os << "/>\n";
    }
    os << "    </P" << (*s)[1] << ">\n";
  }
  for (const std::string& p : pieces) os << "    <Piece Source=\"" << p << "\"/>\n";
  os << "  </PUnstructuredGrid>\n</VTKFile>\n";
  return os.str();
}

// Every rank with elements writes its piece through write_piece(path), then rank 0 writes the index of the
// pieces written. A piece or the index that cannot be written (disk full, permissions) fails every rank, not just
// its writer.
void write_pieces_and_index(const std::filesystem::path& folder, const std::string& stem, bool has_elements,
                            const std::function<void(const std::string& path)>& write_piece) {
  const ElementPartition part = rank_partition();
  const std::vector<std::string> names = parallel_vtu_files(stem, part.parts);
  int wrote = has_elements ? 1 : 0;
  on_every_rank([&] {
    if (wrote) write_piece((folder / names[static_cast<std::size_t>(part.part) + 1]).string());
  });
  std::vector<int> all(static_cast<std::size_t>(part.parts));
  MPI_Gather(&wrote, 1, MPI_INT, all.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD);
  on_every_rank([&] {
    if (part.part != 0) return;
    std::vector<std::string> written;
    for (int r = 0; r < part.parts; ++r)
      if (all[static_cast<std::size_t>(r)]) written.push_back(names[static_cast<std::size_t>(r) + 1]);
    require(!written.empty(), "vtk: no rank has elements to write");
    const std::string index = pvtu_index(folder / written.front(), written);
    write_file_atomically((folder / names[0]).string(), [&](std::ostream& os) { os << index; });
  });
}

template <int D>
int element_count(const LRSpline<D>& g) {
  return g.num_elements();
}
template <int D>
int element_count(const HierarchicalSpline<D>& g) {
  return g.space().num_elements();
}

// The pieces of a locally refined space: this rank's run of the element list (the elements it assembled),
// tessellated by the serial writer of refined geometries.
template <int D, class Geometry>
void write_refined_pieces(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                          const Geometry& geometry, const std::vector<ParallelField>& fields) {
  const int elements = element_count(geometry);
  require(elements == space.num_elements(), "vtk: the geometry has " + std::to_string(elements) +
                                                " elements, the analysis space " + std::to_string(space.num_elements()));
  const std::pair<int, int> run = rank_partition().layers(space.num_elements());
  io::LRVtkOptions options;
  options.first_element = run.first;
  options.last_element = run.second;
  std::vector<io::VtkPointField> vtk;
  for (const ParallelField& f : fields)
    vtk.push_back({f.name, f.components, [&space, &f](int, std::span<const double> u, std::span<double> out) {
                     refined_field_value(space, f.coefs, f.components, io::param_of<D>(u), out.data());
                   }});
  write_pieces_and_index(folder, stem, run.first < run.second, [&](const std::string& path) {
    if constexpr (std::is_same_v<Geometry, LRSpline<D>>)
      io::write_lr_vtu(path, AnyLRSpline(geometry), options, vtk);
    else
      io::write_hierarchical_vtu(path, {AnyHierarchicalSpline(geometry)}, options, vtk);
  });
}

}  // namespace

template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem,
                        const MultipatchSpace<D>& space, const std::vector<ParallelField>& fields) {
  const ElementPartition part = rank_partition();
  std::vector<AnySpline> pieces;
  std::vector<int> patch_of;
  for (int p = 0; p < space.num_patches(); ++p) {
    const TensorSpline<D>& g = space.patches[static_cast<std::size_t>(p)].geometry;
    const std::vector<double> breaks = g.knots(D - 1).breakpoints();
    const std::pair<int, int> layers = part.layers(static_cast<int>(breaks.size()) - 1);
    if (layers.first == layers.second) continue;
    Box<D> box;
    for (int k = 0; k < D; ++k) {
      const std::vector<double> b = g.knots(k).breakpoints();
      box.lo[k] = b.front();
      box.hi[k] = b.back();
    }
    box.lo[D - 1] = breaks[static_cast<std::size_t>(layers.first)];
    box.hi[D - 1] = breaks[static_cast<std::size_t>(layers.second)];
    pieces.emplace_back(sub_patch(g, box));
    patch_of.push_back(p);
  }
  // Per field and patch the solution as a spline on the patch's parameters (the pieces keep them).
  std::vector<std::vector<TensorSpline<D>>> splines(fields.size());
  std::vector<io::VtkPointField> vtk;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    for (int p : patch_of)
      splines[f].push_back(solution_field(space.patches[static_cast<std::size_t>(p)],
                                          patch_coefs(space, p, fields[f].coefs, fields[f].components),
                                          fields[f].components));
    vtk.push_back({fields[f].name, fields[f].components,
                   [&s = splines[f]](int piece, std::span<const double> u, std::span<double> out) {
                     s[static_cast<std::size_t>(piece)].eval(io::param_of<D>(u), out.data());
                   }});
  }
  write_pieces_and_index(folder, stem, !pieces.empty(),
                         [&](const std::string& path) { io::write_vtu(path, pieces, {}, vtk); });
}

template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const LRSpline<D>& geometry, const std::vector<ParallelField>& fields) {
  write_refined_pieces<D>(folder, stem, space, geometry, fields);
}

template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const HierarchicalSpline<D>& geometry, const std::vector<ParallelField>& fields) {
  write_refined_pieces<D>(folder, stem, space, geometry, fields);
}

template <int D>
void write_parallel_vtu(const std::filesystem::path& folder, const std::string& stem, const RefinedSpace<D>& space,
                        const std::vector<LRSpline<D>>& blocks, const std::vector<ParallelField>& fields) {
  // Per block the index of its first element in the space.
  std::vector<int> offset{0};
  for (const LRSpline<D>& b : blocks) offset.push_back(offset.back() + b.num_elements());
  bool same = offset.back() == space.num_elements() && space.blocks.size() == blocks.size();
  for (int e = 0; same && e < space.num_elements(); ++e) {
    const RefinedElement<D>& el = space.elements[static_cast<std::size_t>(e)];
    same = el.block >= 0 && el.block < static_cast<int>(blocks.size());
    const int local = same ? e - offset[static_cast<std::size_t>(el.block)] : -1;
    same = same && local >= 0 && local < blocks[static_cast<std::size_t>(el.block)].num_elements() &&
           el.box.lo == blocks[static_cast<std::size_t>(el.block)].element(local).lo &&
           el.box.hi == blocks[static_cast<std::size_t>(el.block)].element(local).hi;
  }
  require(same, "vtk: the blocks' " + std::to_string(offset.back()) + " elements are not the multi-block space's " +
                    std::to_string(space.num_elements()));
  const std::pair<int, int> run = rank_partition().layers(space.num_elements());
  // The blocks the run meets, each with its part of the run in its own element ids.
  std::vector<AnyLRSpline> pieces;
  std::vector<int> block_of;
  io::LRVtkOptions options;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const int first = std::max(run.first, offset[b]), last = std::min(run.second, offset[b + 1]);
    if (first >= last) continue;
    pieces.emplace_back(blocks[b]);
    block_of.push_back(static_cast<int>(b));
    options.runs.emplace_back(first - offset[b], last - offset[b]);
  }
  std::vector<io::VtkPointField> vtk;
  for (const ParallelField& f : fields)
    vtk.push_back({f.name, f.components, [&](int piece, std::span<const double> u, std::span<double> out) {
                     const auto b = static_cast<std::size_t>(block_of[static_cast<std::size_t>(piece)]);
                     const Param<D> x = io::param_of<D>(u);
                     const int element = offset[b] + blocks[b].evaluator().find_element(x);
                     refined_field_value(space, element, f.coefs, f.components, x, out.data());
                   }});
  write_pieces_and_index(folder, stem, !pieces.empty(), [&](const std::string& path) { io::write_lr_vtu(path, pieces, options, vtk); });
}

template void write_parallel_vtu(const std::filesystem::path&, const std::string&, const MultipatchSpace<2>&,
                                 const std::vector<ParallelField>&);
template void write_parallel_vtu(const std::filesystem::path&, const std::string&, const MultipatchSpace<3>&,
                                 const std::vector<ParallelField>&);
#define TRIVAR_REFINED_PARALLEL_VTU(D)                                                                             \
  template void write_parallel_vtu(const std::filesystem::path&, const std::string&, const RefinedSpace<D>&,        \
                                   const LRSpline<D>&, const std::vector<ParallelField>&);                          \
  template void write_parallel_vtu(const std::filesystem::path&, const std::string&, const RefinedSpace<D>&,        \
                                   const std::vector<LRSpline<D>>&, const std::vector<ParallelField>&);             \
  template void write_parallel_vtu(const std::filesystem::path&, const std::string&, const RefinedSpace<D>&,        \
                                   const HierarchicalSpline<D>&, const std::vector<ParallelField>&);
TRIVAR_REFINED_PARALLEL_VTU(2)
TRIVAR_REFINED_PARALLEL_VTU(3)
#undef TRIVAR_REFINED_PARALLEL_VTU

}  // namespace trivar
