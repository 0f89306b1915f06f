#include "trivar/cad/step_transfer.hpp"

#include <Interface_Static.hxx>
#include <Resource_Manager.hxx>
#include <ShapeProcess_Context.hxx>

#include <mutex>
#include <string>

namespace trivar::cad {

namespace {

// A resource name with no file behind it: the kernel keeps one in-memory manager per name (the last one asked
// for), which this file fills before each transfer.
constexpr const char* kResource = "trivarSTEPHealing";
constexpr const char* kSequence = "FromSTEP";

// The kernel's default STEP healing (XSAlgo_AlgoContainer::ProcessShape without a resource file: ShapeFix_Shape
// at the file's precision, no same-parameter fix of wires, no open solids), as a ShapeProcess sequence, minus
// the two fixes that are quadratic in the loops of a face and whose defects the validity check finds.
void fill(Resource_Manager& rm) {
  const std::string op = std::string(kSequence) + ".FixShape.";
  rm.SetResource((std::string(kSequence) + ".exec.op").c_str(), "FixShape");
  rm.SetResource((op + "Tolerance3d").c_str(), "&Runtime.Tolerance");
  rm.SetResource((op + "MaxTolerance3d").c_str(), "&Runtime.MaxTolerance");
  rm.SetResource((op + "FixEdgeSameParameterMode").c_str(), 0);
  rm.SetResource((op + "CreateOpenSolidMode").c_str(), 0);
  rm.SetResource((op + "FixNonAdjacentIntersectingEdgesMode").c_str(), 0);
  rm.SetResource((op + "FixIntersectingWiresMode").c_str(), 0);
}

std::mutex transfer_mutex;

}  // namespace

int transfer_roots(STEPControl_Reader& reader) {
  const std::lock_guard<std::mutex> lock(transfer_mutex);
  const std::string resource = Interface_Static::CVal("read.step.resource.name");
  const std::string sequence = Interface_Static::CVal("read.step.sequence");
  // The transfer asks the kernel for the manager of this name and gets the one filled here (same name, no file).
  ShapeProcess_Context context;
  fill(*context.LoadResourceManager(kResource));
  Interface_Static::SetCVal("read.step.resource.name", kResource);
  Interface_Static::SetCVal("read.step.sequence", kSequence);
  struct Restore {
    const std::string &resource, &sequence;
    ~Restore() {
      Interface_Static::SetCVal("read.step.resource.name", resource.c_str());
      Interface_Static::SetCVal("read.step.sequence", sequence.c_str());
    }
  } restore{resource, sequence};
  return reader.TransferRoots();
}

}  // namespace trivar::cad
