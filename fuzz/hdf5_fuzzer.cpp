// The HDF5 reader over libhdf5 from a file image in memory (H5Pset_fapl_core +
// H5Pset_file_image): ACRONYM's numeric datasets read as the grasp importer reads them.
// ImportError is the documented outcome. libhdf5 itself is not instrumented (Debian's build): the
// harness finds faults in our use of it, and crashes inside it surface as findings all the same.
// Variable-length strings (Hdf5File::text, object/file) are not fuzzed: Debian's libhdf5 1.10.8
// overflows a heap buffer in H5HG_read on a damaged global heap (fuzz/known/hdf5,
// docs/fuzzing.md), which no caller can guard against.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "visgrab/importers/hdf5_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto h5 =
        visgrab::importers::Hdf5File::fromBytes(visgrab::fuzz::asText(data, size), "fuzz.h5");
    for (const char* key : {"grasps/transforms", "grasps/qualities/flex/object_in_gripper",
                            "object/scale", "object/com", "object/inertia"}) {
      try {
        const auto array = h5.numbers(key);
      } catch (const visgrab::importers::ImportError&) {
      }
    }
  } catch (const visgrab::importers::ImportError&) {
  }
  return 0;
}
