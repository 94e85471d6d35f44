#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace visgrab::importers::detail {

/// The most chunks a dataset this reader reads may have (ACRONYM's have 2 to 16): libhdf5 keeps a
/// record of every chunk a read touches, and the checks here inflate each chunk.
inline constexpr std::uint64_t kMaxHdf5Chunks = 65536;

/// The parts of an HDF5 file's metadata that Debian's libhdf5 1.10.8 trusts before it checks
/// them against the file's end, read and checked here from the file's bytes first
/// (docs/fuzzing.md, item 7). libhdf5 allocates a block of metadata at the size the file claims
/// and only then finds it past the end of the file, so a damaged file of a few kB made it ask for
/// up to 2^56 bytes, and a heap whose data address was undefined crashed it. Checked, for each
/// object Hdf5File opens (the root group, each group on a path, the dataset) before libhdf5 reads
/// it:
/// - the superblock's driver information block (versions 0-1) lies inside the file, its
///   extension (versions 2-3) is an object header checked as the others (checkRoot);
/// - every continuation chunk of its object header (versions 1 and 2) lies inside the file;
/// - a symbol-table group's local heap (where libhdf5 keeps the names of its members) has its
///   signature, its data block lies inside the file and its free list stays inside the heap
///   without coming back to a block;
/// - a dataset's layout (versions 3 and 4; others and virtual datasets refused): compact data
///   inside its message, contiguous data inside the file, chunks of at most kMaxArrayBytes and
///   no dimension of 0; fill values inside their message; external storage refused;
/// - a chunked dataset's (layout 3) B-tree: nodes inside the file with their signature, type and
///   level, none reached twice; chunks inside the file, none listed twice, at most
///   kMaxHdf5Chunks; its filters (deflate, shuffle, fletcher32; others and a shared pipeline
///   refused) undone here, zlib inflating, and each chunk giving exactly one chunk's bytes;
/// - a variable-length string's global heap object (checkVariableLengthString).
/// An object header of another version is left to libhdf5, which refuses it before allocating. The
/// file's sizes of offsets and lengths and its base address come from the superblock (versions 0 to
/// 3), found at byte 0, 512, 1024, ... as HDF5 looks for it.
class Hdf5Structure {
 public:
  /// `image` must outlive this; `name` is the file's name in messages.
  Hdf5Structure(std::string_view image, std::string name);

  /// True if the superblock was found (the other calls then check; else they do nothing and
  /// libhdf5 reports the file as it sees it).
  bool found() const { return found_; }
  /// Checks the root group's object header (and, for a version 0 or 1 superblock, the name heap
  /// its symbol table entry caches). @throws ImportError naming the file and what is damaged.
  void checkRoot() const;
  /// Where a dataset's values are, as its layout message says (compact: inside the message;
  /// contiguous: at an address, or nowhere yet). Positions are bytes of the image.
  struct Storage {
    bool known = false;  // a compact or contiguous layout with its data written
    std::uint64_t at = 0;
    std::uint64_t bytes = 0;
    std::uint64_t sequenceElementBytes = 0;  // a variable-length type's element size (0: none)
    bool sharedDatatype = false;             // its datatype message names a committed type
    bool datatypeSeen = false;               // libhdf5 uses the first datatype message
    bool layoutSeen = false;                 // and the first layout message
    // A chunked dataset of layout version 3: its B-tree's address (undefined: no chunk yet),
    // the layout's dimensionality (rank + 1) and one chunk's bytes before its filters.
    bool chunked = false;
    std::uint64_t chunkTree = 0;
    std::uint64_t chunkDims = 0;
    std::uint64_t chunkBytes = 0;
    // The filter pipeline's filters in the order they were applied when writing (the first
    // pipeline message; libhdf5 uses it).
    std::vector<unsigned> filters;
    bool filtersSeen = false;
    bool filtersShared = false;  // the pipeline is a shared message (kept elsewhere)
  };
  /// Checks the object header at `address` (relative to the base address, as libhdf5 reports it),
  /// called `what` in messages ("'grasps'"), and returns where its values are (a dataset's).
  /// @throws ImportError.
  Storage checkObject(std::uint64_t address, const std::string& what) const;
  /// Checks the variable-length string that a scalar dataset stored at `storage` refers to: its
  /// global heap collection ("GCOL") lies inside the file, each object of the collection inside
  /// the collection, and the referenced object exists and holds the string's length. libhdf5
  /// copies an object at the size the collection claims for it without these checks (item 6 of
  /// docs/fuzzing.md: a read 4,040 bytes past its buffer). @throws ImportError.
  void checkVariableLengthString(const Storage& storage, const std::string& what) const;

 private:
  // The little-endian unsigned number of `bytes` bytes at absolute byte `at`; throws if the file
  // ends before it.
  std::uint64_t number(std::uint64_t at, std::size_t bytes, const std::string& what) const;
  // True if [address, address + length) relative to the base lies inside the file.
  bool inside(std::uint64_t address, std::uint64_t length) const;
  bool undefined(std::uint64_t address) const;
  void checkHeap(std::uint64_t address, const std::string& what) const;
  // One header message: its type, flags (0x02: shared), and data (bytes of the image).
  struct Message {
    unsigned type = 0;
    unsigned flags = 0;
    std::uint64_t at = 0;
    std::uint64_t bytes = 0;
  };
  void checkMessage(const Message& m, const std::string& what, std::uint64_t* continuation,
                    std::uint64_t* continuationLength, Storage* storage) const;
  void checkLayout(const Message& m, const std::string& what, Storage* storage) const;
  void checkFilters(const Message& m, const std::string& what, Storage* storage) const;
  // Walks the version 1 B-tree of a chunked dataset (layout version 3): every node inside the
  // file with its signature, type and level, no node visited twice, every chunk inside the file
  // at the size its key claims and, through its filters (deflate inflated here), exactly one
  // chunk's bytes.
  void checkChunkTree(const Storage& storage, const std::string& what) const;
  // The bytes chunk `data` gives through `storage`'s filters not skipped by `mask`.
  std::uint64_t unfilteredBytes(std::string_view data, std::uint64_t mask, const Storage& storage,
                                const std::string& what, std::uint64_t address) const;
  [[noreturn]] void unsupported(const std::string& what, const std::string& why) const;
  [[noreturn]] void damaged(const std::string& what, const std::string& why) const;
  // "<thing> (at byte A) lies outside the file of N bytes"; "<thing> claims B bytes at byte A,
  // outside the file of N bytes". An undefined address reads "(undefined)".
  [[noreturn]] void outside(const std::string& what, const std::string& thing,
                            std::uint64_t address) const;
  [[noreturn]] void claimsOutside(const std::string& what, const std::string& thing,
                                  std::uint64_t bytes, std::uint64_t address) const;
  std::string byteText(std::uint64_t address) const;
  std::string fileText() const;

  std::string_view image_;
  std::string name_;
  bool found_ = false;
  std::size_t offsetBytes_ = 8;
  std::size_t lengthBytes_ = 8;
  std::uint64_t base_ = 0;
  std::uint64_t rootHeader_ = 0;
  std::optional<std::uint64_t> driverInfo_;  // superblock 0-1 (the address, maybe undefined)
  std::optional<std::uint64_t> extension_;   // superblock 2-3 (the address, maybe undefined)
  std::uint64_t rootHeap_ = 0;
  bool rootHeapCached_ = false;
};

}  // namespace visgrab::importers::detail
