#include "visgrab/importers/hdf5_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <type_traits>
#include <utility>

#include "visgrab/importers/hdf5_structure.hpp"
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
// Each object on the way is checked from the file's bytes (Hdf5Structure::checkObject) before
// libhdf5 reads it: the root group when the file is opened, then each link's target as soon as
// its address is known. Soft and external links are refused: their targets would be read
// unchecked (and an external link opens another file).
// `storage` (if given) receives where the last object's values are.
bool linkExists(hid_t file, const detail::Hdf5Structure& structure, const std::string& fileName,
                const std::string& path, detail::Hdf5Structure::Storage* storage = nullptr) {
  std::size_t at = 0;
  while (true) {
    const std::size_t slash = path.find('/', at);
    const std::string prefix = path.substr(0, slash);
    if (prefix.empty() || H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    H5L_info_t link;
    if (H5Lget_info(file, prefix.c_str(), &link, H5P_DEFAULT) < 0) {
      throw ImportError(fileName + ": '" + prefix + "' cannot be read: " + hdf5Reason());
    }
    if (link.type != H5L_TYPE_HARD) {
      throw ImportError(fileName + ": '" + prefix +
                        "' is a soft or external link (this reader follows hard links only)");
    }
    const auto values = structure.checkObject(link.u.address, "'" + prefix + "'");
    if (storage != nullptr) *storage = values;
    if (slash == std::string::npos) return true;
    at = slash + 1;
  }
}

// A chunked dataset of shape `dims` may have at most detail::kMaxHdf5Chunks chunks: libhdf5 keeps a
// record (with a dataspace) of every chunk a read touches, written or not, and a damaged shape
// of 2.6 million values in chunks of 2 took more than 2 GB (docs/fuzzing.md, item 7).
void checkChunkCount(hid_t plist, const std::vector<hsize_t>& dims, const std::string& where) {
  std::vector<hsize_t> chunk(H5S_MAX_RANK);
  const int rank = H5Pget_chunk(plist, H5S_MAX_RANK, chunk.data());
  if (rank != static_cast<int>(dims.size())) {
    throw ImportError(where + " is damaged: its chunks have " + std::to_string(rank) +
                      " dimensions, its shape " + std::to_string(dims.size()));
  }
  const auto text = [](const hsize_t* values, std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n; ++i) out += (i == 0 ? "" : " x ") + std::to_string(values[i]);
    return out;
  };
  if (std::find(dims.begin(), dims.end(), hsize_t{0}) != dims.end()) return;  // nothing to read
  std::uint64_t chunks = 1;
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (chunk[i] == 0) throw ImportError(where + " is damaged: a chunk dimension of 0");
    chunks *= (dims[i] + chunk[i] - 1) / chunk[i];  // the shape's count is bounded: no overflow
    if (chunks > detail::kMaxHdf5Chunks) {
      throw ImportError(where + " is stored in more than " +
                        std::to_string(detail::kMaxHdf5Chunks) + " chunks (chunks of " +
                        text(chunk.data(), dims.size()) + " for a shape of " +
                        text(dims.data(), dims.size()) + "), more than this reader reads");
    }
  }
}

// libhdf5 1.10.8 copies a compact dataset's values from the data its layout message holds
// without checking that it holds them all (a compact dataset of 0 bytes with 3 values made it
// read from a null pointer: docs/fuzzing.md, item 7). The values need `bytes` bytes: a compact
// dataset must hold exactly those, a contiguous one at least those once written; a chunked one
// of shape `*dims` (when given) at most detail::kMaxHdf5Chunks chunks (checkChunkCount).
void checkStorage(hid_t dataset, std::uint64_t bytes, const std::vector<hsize_t>* dims,
                  const std::string& where) {
  Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  if (!plist.ok()) throw ImportError(where + " cannot be read: " + hdf5Reason());
  const H5D_layout_t layout = H5Pget_layout(plist.get());
  if (layout == H5D_CHUNKED && dims != nullptr) checkChunkCount(plist.get(), *dims, where);
  if (layout != H5D_COMPACT && layout != H5D_CONTIGUOUS) return;
  const hsize_t stored = H5Dget_storage_size(dataset);
  if ((layout == H5D_COMPACT && stored != bytes) ||
      (layout == H5D_CONTIGUOUS && stored != 0 && stored < bytes)) {
    throw ImportError(where + " is damaged: its values need " + std::to_string(bytes) +
                      " bytes, its " + (layout == H5D_COMPACT ? "compact" : "contiguous") +
                      " storage holds " + std::to_string(stored));
  }
}

}  // namespace

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : name_(std::move(other.name_)),
      image_(std::move(other.image_)),
      file_(std::exchange(other.file_, -1)) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    if (file_ >= 0) {
      QuietHdf5 quiet;
      H5Fclose(file_);
    }
    name_ = std::move(other.name_);
    image_ = std::move(other.image_);
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
  {
    QuietHdf5 quiet;
    if (H5Fis_hdf5(file.string().c_str()) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      throw ImportError(file.string() + ": not an HDF5 file (expected an .h5 file)");
    }
  }
  // Read whole, so that its metadata can be checked before libhdf5 trusts it (Hdf5Structure).
  return fromImage(readFileBytes(file, kMaxHdf5FileBytes), file.string(), "cannot open it");
}

Hdf5File Hdf5File::fromBytes(std::string_view bytes, const std::string& name) {
  if (bytes.size() > kMaxHdf5FileBytes) {
    throw ImportError(name + ": the file has " + std::to_string(bytes.size()) +
                      " bytes, more than the " + std::to_string(kMaxHdf5FileBytes) +
                      " this reader accepts");
  }
  return fromImage(std::string(bytes), name, "not a readable HDF5 file");
}

Hdf5File Hdf5File::fromImage(std::string bytes, const std::string& name,
                             const std::string& failure) {
  Hdf5File out;
  out.name_ = name;
  out.image_ = std::move(bytes);
  detail::Hdf5Structure(out.image_, name).checkRoot();
  QuietHdf5 quiet;
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // HDF5's core driver copies the image; no backing store is written.
  if (!fapl.ok() || H5Pset_fapl_core(fapl.get(), 65536, 0) < 0 ||
      H5Pset_file_image(fapl.get(), out.image_.data(), out.image_.size()) < 0) {
    throw ImportError(name + ": cannot hand the file image to HDF5: " + hdf5Reason());
  }
  // The core driver tells files apart by name: two images open under one name (the same file
  // opened twice) would be refused as "file already exists". Each image gets its own.
  static unsigned long long opened = 0;  // guarded by the library lock (quiet)
  const std::string image = "visgrab-hdf5-image-" + std::to_string(++opened);
  out.file_ = H5Fopen(image.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (out.file_ < 0) throw ImportError(name + ": " + failure + ": " + hdf5Reason());
  return out;
}

bool Hdf5File::hasDataset(const std::string& path) const {
  QuietHdf5 quiet;
  if (!linkExists(file_, detail::Hdf5Structure(image_, name_), name_, path)) {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  H5O_info_t info;
  const bool dataset =
      H5Oget_info_by_name2(file_, path.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) >= 0 &&
      info.type == H5O_TYPE_DATASET;
  H5Eclear2(H5E_DEFAULT);
  return dataset;
}

NdArray Hdf5File::numbers(const std::string& path, int rank, const std::string& expected) const {
  const std::string where = name_ + ": dataset '" + path + "'";
  const std::string wanted = expected.empty() ? "" : " (expected " + expected + ")";
  QuietHdf5 quiet;
  if (!linkExists(file_, detail::Hdf5Structure(image_, name_), name_, path))
    throw ImportError(where + " is missing" + wanted);
  Handle dataset(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.ok()) throw ImportError(where + " is not a dataset: " + hdf5Reason());
  Handle type(H5Dget_type(dataset.get()), H5Tclose);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!type.ok() || !space.ok()) throw ImportError(where + " cannot be read: " + hdf5Reason());
  const H5T_class_t typeClass = H5Tget_class(type.get());
  if (typeClass != H5T_INTEGER && typeClass != H5T_FLOAT) {
    throw ImportError(where + " is not numeric (integer or float)" + wanted);
  }
  // A numeric element is at most 16 bytes (a long double); HDF5 sizes its conversion buffer by
  // the file's element size, which a damaged file can set to gigabytes (a 4 GB calloc, item 7).
  const std::size_t elementBytes = H5Tget_size(type.get());
  if (elementBytes == 0 || elementBytes > 16) {
    throw ImportError(where + " has elements of " + std::to_string(elementBytes) +
                      " bytes (a number has 1 to 16)" + wanted);
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
  checkStorage(dataset.get(), count * elementBytes, &dims, where);
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
  const detail::Hdf5Structure structure(image_, name_);
  detail::Hdf5Structure::Storage storage;
  if (!linkExists(file_, structure, name_, path, &storage)) {
    throw ImportError(where + " is missing (expected a string)");
  }
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
    structure.checkVariableLengthString(storage, "dataset '" + path + "'");
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
  checkStorage(dataset.get(), size, nullptr, where);  // one value: one chunk at most
  std::string out(size, '\0');
  if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw ImportError(where + " cannot be read: " + hdf5Reason());
  }
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

}  // namespace visgrab::importers
