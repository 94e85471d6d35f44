#include "visgrab/importers/hdf5_file.hpp"

#include <hdf5.h>

#include <cstdint>
#include <mutex>
#include <type_traits>
#include <utility>

#include "visgrab/importers/npy.hpp"

namespace visgrab::importers {

static_assert(std::is_same_v<hid_t, std::int64_t>, "Hdf5File stores hid_t as int64_t");

namespace {

// Debian's serial libhdf5 is not thread-safe: every call of this file holds this lock.
std::mutex& hdf5Mutex() {
  static std::mutex m;
  return m;
}

// Silences HDF5's printing of its error stack while alive (restoring what was set before), and
// holds the library lock.
class QuietHdf5 {
 public:
  QuietHdf5() : lock_(hdf5Mutex()) {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

herr_t innermostError(unsigned n, const H5E_error2_t* e, void* out) {
  if (n == 0 && e->desc != nullptr) *static_cast<std::string*>(out) = e->desc;
  return 0;
}

// HDF5's reason for the failure that just happened (the innermost entry of its error stack).
std::string hdf5Reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermostError, &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? std::string("HDF5 gives no reason") : "HDF5: " + reason;
}

// Closes an HDF5 id with its close function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// True if every group on `path` and the last link exist (H5Lexists needs each step checked).
bool linkExists(hid_t file, const std::string& path) {
  std::size_t at = 0;
  while (true) {
    const std::size_t slash = path.find('/', at);
    const std::string prefix = path.substr(0, slash);
    if (prefix.empty() || H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    at = slash + 1;
  }
}

}  // namespace

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : name_(std::move(other.name_)), file_(std::exchange(other.file_, -1)) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    if (file_ >= 0) {
      QuietHdf5 quiet;
      H5Fclose(file_);
    }
    name_ = std::move(other.name_);
    file_ = std::exchange(other.file_, -1);
  }
  return *this;
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) {
    QuietHdf5 quiet;
    H5Fclose(file_);
  }
}

Hdf5File Hdf5File::open(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw ImportError(file.string() + ": no such file");
  }
  QuietHdf5 quiet;
  if (H5Fis_hdf5(file.string().c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw ImportError(file.string() + ": not an HDF5 file (expected an .h5 file)");
  }
  Hdf5File out;
  out.name_ = file.string();
  out.file_ = H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (out.file_ < 0) throw ImportError(file.string() + ": cannot open it: " + hdf5Reason());
  return out;
}

Hdf5File Hdf5File::fromBytes(std::string_view bytes, const std::string& name) {
  QuietHdf5 quiet;
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (!fapl.ok() || H5Pset_fapl_core(fapl.get(), 65536, 0) < 0 ||
      H5Pset_file_image(fapl.get(), const_cast<char*>(bytes.data()), bytes.size()) < 0) {
    throw ImportError(name + ": cannot hand the file image to HDF5: " + hdf5Reason());
  }
  Hdf5File out;
  out.name_ = name;
  out.file_ = H5Fopen(name.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (out.file_ < 0) throw ImportError(name + ": not a readable HDF5 file: " + hdf5Reason());
  return out;
}

bool Hdf5File::hasDataset(const std::string& path) const {
  QuietHdf5 quiet;
  if (!linkExists(file_, path)) {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  H5O_info_t info;
  const bool dataset = H5Oget_info_by_name(file_, path.c_str(), &info, H5P_DEFAULT) >= 0 &&
                       info.type == H5O_TYPE_DATASET;
  H5Eclear2(H5E_DEFAULT);
  return dataset;
}

NdArray Hdf5File::numbers(const std::string& path, int rank, const std::string& expected) const {
  const std::string where = name_ + ": dataset '" + path + "'";
  const std::string wanted = expected.empty() ? "" : " (expected " + expected + ")";
  QuietHdf5 quiet;
  if (!linkExists(file_, path)) throw ImportError(where + " is missing" + wanted);
  Handle dataset(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.ok()) throw ImportError(where + " is not a dataset: " + hdf5Reason());
  Handle type(H5Dget_type(dataset.get()), H5Tclose);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!type.ok() || !space.ok()) throw ImportError(where + " cannot be read: " + hdf5Reason());
  const H5T_class_t typeClass = H5Tget_class(type.get());
  if (typeClass != H5T_INTEGER && typeClass != H5T_FLOAT) {
    throw ImportError(where + " is not numeric (integer or float)" + wanted);
  }
  const H5S_class_t spaceClass = H5Sget_simple_extent_type(space.get());
  if (spaceClass != H5S_SCALAR && spaceClass != H5S_SIMPLE) {
    throw ImportError(where + " holds no values" + wanted);
  }
  const int ndims = H5Sget_simple_extent_ndims(space.get());
  if (ndims < 0 || ndims > H5S_MAX_RANK) {
    throw ImportError(where + " has an unreadable shape: " + hdf5Reason());
  }
  std::vector<hsize_t> dims(static_cast<std::size_t>(ndims));
  if (ndims > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
    throw ImportError(where + " has an unreadable shape: " + hdf5Reason());
  }
  NdArray out;
  out.dtype = typeClass == H5T_INTEGER ? "integer" : "float";
  std::size_t count = 1;
  for (const hsize_t d : dims) {
    out.shape.push_back(static_cast<std::size_t>(d));
    if (d != 0 && count > kMaxArrayBytes / sizeof(double) / d) {
      throw ImportError(where + " is larger than this reader accepts (" +
                        std::to_string(kMaxArrayBytes) + " bytes)");
    }
    count *= static_cast<std::size_t>(d);
  }
  if (rank >= 0 && ndims != rank) {
    throw ImportError(where + " has shape " + out.shapeText() + wanted);
  }
  out.values.resize(count);
  if (count > 0 && H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                           out.values.data()) < 0) {
    throw ImportError(where + " cannot be read: " + hdf5Reason());
  }
  return out;
}

std::string Hdf5File::text(const std::string& path) const {
  const std::string where = name_ + ": dataset '" + path + "'";
  QuietHdf5 quiet;
  if (!linkExists(file_, path)) throw ImportError(where + " is missing (expected a string)");
  Handle dataset(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.ok()) throw ImportError(where + " is not a dataset: " + hdf5Reason());
  Handle type(H5Dget_type(dataset.get()), H5Tclose);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!type.ok() || !space.ok()) throw ImportError(where + " cannot be read: " + hdf5Reason());
  if (H5Tget_class(type.get()) != H5T_STRING) throw ImportError(where + " is not a string");
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  if (points != 1) {
    throw ImportError(where + " holds " + std::to_string(points) + " values, expected one string");
  }
  Handle memType(H5Tcopy(H5T_C_S1), H5Tclose);
  // The file's character set (h5py writes UTF-8): HDF5 converts no string between sets.
  if (H5Tset_cset(memType.get(), H5Tget_cset(type.get())) < 0) {
    throw ImportError(where + " cannot be read: " + hdf5Reason());
  }
  if (H5Tis_variable_str(type.get()) > 0) {
    if (H5Tset_size(memType.get(), H5T_VARIABLE) < 0) {
      throw ImportError(where + " cannot be read: " + hdf5Reason());
    }
    char* value = nullptr;
    if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) < 0) {
      throw ImportError(where + " cannot be read: " + hdf5Reason());
    }
    std::string out = value != nullptr ? value : "";
    H5free_memory(value);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > 65536) {
    throw ImportError(where + " is a string of " + std::to_string(size) + " bytes (at most 65536)");
  }
  if (H5Tset_size(memType.get(), size) < 0 || H5Tset_strpad(memType.get(), H5T_STR_NULLPAD) < 0) {
    throw ImportError(where + " cannot be read: " + hdf5Reason());
  }
  std::string out(size, '\0');
  if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw ImportError(where + " cannot be read: " + hdf5Reason());
  }
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

}  // namespace visgrab::importers
