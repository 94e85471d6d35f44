// The HDF5 reader over libhdf5 from a file image in memory (H5Pset_fapl_core +
// H5Pset_file_image): ACRONYM's numeric datasets and its variable-length string (object/file)
// read as the grasp importer and `db from-acronym` read them. ImportError is the documented
// outcome. libhdf5 itself is not instrumented (Debian's build): the harness finds faults in our
// use of it and in the metadata checks made before it reads (Hdf5Structure, docs/fuzzing.md item
// 7), and crashes inside it surface as findings all the same.
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
    try {
      const auto file = h5.text("object/file");
    } catch (const visgrab::importers::ImportError&) {
    }
  } catch (const visgrab::importers::ImportError&) {
  }
  return 0;
}
