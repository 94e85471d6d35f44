#include "visgrab/importers/hdf5_structure.hpp"

#include <zlib.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "visgrab/importers/npy.hpp"

// The layouts read here are those of the HDF5 File Format Specification (version 3.0): the
// superblock (versions 0-3), object headers (versions 1 and 2, with their continuation chunks),
// the symbol table, continuation and data layout messages, and the local heap.
namespace visgrab::importers::detail {

namespace {

constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
constexpr unsigned kContinuationMessage = 0x10;
constexpr unsigned kSymbolTableMessage = 0x11;
constexpr unsigned kLayoutMessage = 0x08;
constexpr unsigned kDatatypeMessage = 0x03;
constexpr unsigned kOldFillValueMessage = 0x04;
constexpr unsigned kFillValueMessage = 0x05;
constexpr unsigned kExternalFilesMessage = 0x07;
// A chunk B-tree's depth and node count: far beyond what the largest array this reader accepts
// needs (kMaxArrayBytes in chunks of one element, 64 entries a node), and they stop a damaged
// tree that points back into itself.
constexpr std::uint64_t kMaxTreeLevel = 32;
// The chunks of one dataset, unfiltered, add up to at most this: twice the largest array the
// readers take (edge chunks hold padding), so that a damaged tree cannot make the check inflate
// without end.
constexpr std::uint64_t kMaxUnfilteredBytes = 2 * kMaxArrayBytes;
constexpr unsigned kFilterPipelineMessage = 0x0B;
constexpr unsigned kDeflateFilter = 1;
constexpr unsigned kFletcher32Filter = 3;

/// The bytes `data` inflates to (zlib stream, as HDF5's deflate filter writes), at most `limit`;
/// `fail` (which throws) is called with why when the stream is damaged or gives more.
template <typename Fail>
std::string inflate(std::string_view data, std::uint64_t limit, const Fail& fail) {
  z_stream z{};
  if (inflateInit(&z) != Z_OK) fail("cannot be inflated (zlib could not start)");
  std::string out(static_cast<std::size_t>(std::min<std::uint64_t>(limit, 1U << 20)) + 1, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  int result = Z_OK;
  std::size_t used = 0;
  while (result == Z_OK) {
    if (used == out.size()) {
      if (used > limit) break;
      out.resize(std::min<std::size_t>(out.size() * 2, static_cast<std::size_t>(limit) + 1));
    }
    z.next_out = reinterpret_cast<Bytef*>(out.data() + used);
    z.avail_out = static_cast<uInt>(out.size() - used);
    result = ::inflate(&z, Z_NO_FLUSH);
    used = out.size() - z.avail_out;
    if (result == Z_BUF_ERROR && z.avail_in == 0) break;  // the stream ends early
  }
  const std::string message = z.msg != nullptr ? z.msg : "";
  inflateEnd(&z);
  if (used > limit) fail("inflates to more than " + std::to_string(limit) + " bytes");
  if (result != Z_STREAM_END && result != Z_BUF_ERROR && result != Z_OK) {
    fail("does not inflate (zlib: " +
         (message.empty() ? "error " + std::to_string(result) : message) + ")");
  }
  out.resize(used);
  return out;
}
constexpr std::size_t kMaxTreeNodes = 1U << 16;
constexpr std::uint64_t kVariableLengthClass = 9;
// A damaged header could chain its continuations in a loop or without end.
constexpr std::size_t kMaxHeaderChunks = 4096;

}  // namespace

Hdf5Structure::Hdf5Structure(std::string_view image, std::string name)
    : image_(image), name_(std::move(name)) {
  // HDF5 looks for the superblock at 0, then at 512 and each doubling.
  std::uint64_t at = 0;
  while (at + kSignature.size() <= image_.size() && image_.substr(at, 8) != kSignature) {
    at = at == 0 ? 512 : at * 2;
  }
  if (at + kSignature.size() > image_.size()) return;
  const std::string sb = "the superblock";
  const auto version = number(at + 8, 1, sb);
  std::uint64_t rootEntry = 0;
  if (version <= 1) {
    offsetBytes_ = number(at + 13, 1, sb);
    lengthBytes_ = number(at + 14, 1, sb);
    rootEntry = at + (version == 0 ? 24 : 28);
  } else if (version <= 3) {
    offsetBytes_ = number(at + 9, 1, sb);
    lengthBytes_ = number(at + 10, 1, sb);
  } else {
    return;  // a later version: left to libhdf5
  }
  for (const std::size_t bytes : {offsetBytes_, lengthBytes_}) {
    if (bytes != 2 && bytes != 4 && bytes != 8) {
      damaged(sb, "it gives addresses or lengths of " + std::to_string(bytes) +
                      " bytes (this reader takes 2, 4 or 8)");
    }
  }
  // libhdf5 takes the superblock's position as the base address that all addresses count from.
  base_ = at;
  if (version <= 1) {
    // Base, free-space, end-of-file and driver addresses, then the root group's symbol table
    // entry: link name offset, object header address, cache type, reserved, scratch pad.
    const std::uint64_t entry = rootEntry + 4 * offsetBytes_;
    driverInfo_ = number(rootEntry + 3 * offsetBytes_, offsetBytes_, sb);
    rootHeader_ = number(entry + offsetBytes_, offsetBytes_, sb);
    if (number(entry + 2 * offsetBytes_, 4, sb) == 1) {
      rootHeapCached_ = true;
      rootHeap_ = number(entry + 2 * offsetBytes_ + 8 + offsetBytes_, offsetBytes_, sb);
    }
  } else {
    extension_ = number(at + 12 + offsetBytes_, offsetBytes_, sb);
    rootHeader_ = number(at + 12 + 3 * offsetBytes_, offsetBytes_, sb);
  }
  found_ = true;
}

std::uint64_t Hdf5Structure::number(std::uint64_t at, std::size_t bytes,
                                    const std::string& what) const {
  if (at > image_.size() || bytes > image_.size() - at) {
    damaged(what, "the file ends at byte " + std::to_string(image_.size()) + ", before byte " +
                      std::to_string(at + bytes) + " it needs");
  }
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < bytes; ++i) {
    value |= std::uint64_t{static_cast<unsigned char>(image_[at + i])} << (8 * i);
  }
  return value;
}

bool Hdf5Structure::inside(std::uint64_t address, std::uint64_t length) const {
  const std::uint64_t size = image_.size();
  if (undefined(address) || base_ > size || address > size - base_) return false;
  return length <= size - base_ - address;
}

bool Hdf5Structure::undefined(std::uint64_t address) const {
  const std::uint64_t all =
      offsetBytes_ >= 8 ? ~std::uint64_t{0} : (std::uint64_t{1} << (8 * offsetBytes_)) - 1;
  return address == all;
}

void Hdf5Structure::damaged(const std::string& what, const std::string& why) const {
  throw ImportError(name_ + ": damaged HDF5 file: " + what + ": " + why);
}

void Hdf5Structure::unsupported(const std::string& what, const std::string& why) const {
  throw ImportError(name_ + ": " + what + ": " + why);
}

std::string Hdf5Structure::byteText(std::uint64_t address) const {
  return undefined(address) ? std::string("(undefined)") : std::to_string(address);
}

std::string Hdf5Structure::fileText() const {
  return "the file of " + std::to_string(image_.size()) + " bytes";
}

void Hdf5Structure::outside(const std::string& what, const std::string& thing,
                            std::uint64_t address) const {
  damaged(what, thing + " (at byte " + byteText(address) + ") lies outside " + fileText());
}

void Hdf5Structure::claimsOutside(const std::string& what, const std::string& thing,
                                  std::uint64_t bytes, std::uint64_t address) const {
  damaged(what, thing + " claims " + std::to_string(bytes) + " bytes at byte " + byteText(address) +
                    ", outside " + fileText());
}

void Hdf5Structure::checkRoot() const {
  if (!found_) return;
  const std::string sb = "the superblock";
  // Versions 0 and 1: a driver information block (version, 3 reserved bytes, its size (4), the
  // driver's name (8), the information), which libhdf5 allocates at the size it claims (a
  // 4 GB block from a 529-byte file, fuzz/regressions/hdf5/driver-info-4GB).
  if (driverInfo_ && !undefined(*driverInfo_)) {
    const std::uint64_t at = *driverInfo_;
    if (!inside(at, 16)) outside(sb, "its driver information block", at);
    const std::uint64_t bytes = 16 + number(base_ + at + 4, 4, sb);
    if (!inside(at, bytes)) claimsOutside(sb, "its driver information block", bytes, at);
  }
  // Versions 2 and 3: the superblock extension is an object header, checked as one.
  if (extension_ && !undefined(*extension_)) checkObject(*extension_, "the superblock extension");
  checkObject(rootHeader_, "the root group");
  if (rootHeapCached_) checkHeap(rootHeap_, "the root group");
}

void Hdf5Structure::checkHeap(std::uint64_t address, const std::string& what) const {
  // Signature "HEAP", version 0, 3 reserved bytes, data size (L), free list offset (L), data
  // address (O).
  const std::uint64_t headerBytes = 8 + 2 * lengthBytes_ + offsetBytes_;
  if (!inside(address, headerBytes)) {
    outside(what, "its name heap", address);
  }
  const std::uint64_t at = base_ + address;
  if (image_.substr(at, 4) != "HEAP" || image_[at + 4] != 0) {
    damaged(what, "no name heap (local heap, version 0) at byte " + std::to_string(address) +
                      ", where its symbol table points");
  }
  const std::uint64_t size = number(at + 8, lengthBytes_, what);
  const std::uint64_t data = number(at + 8 + 2 * lengthBytes_, offsetBytes_, what);
  if (!inside(data, size)) {
    claimsOutside(what, "its name heap", size, data);
  }
  // The free list: offsets into the data, each free block starting with the next one's offset
  // and its own size (L each); 1 (or undefined) ends it. libhdf5 checks each block against the
  // data's size but not for a loop, and allocates a list entry per block it visits: a block
  // pointing at itself took all memory.
  const std::uint64_t none =
      lengthBytes_ >= 8 ? ~std::uint64_t{0} : (std::uint64_t{1} << (8 * lengthBytes_)) - 1;
  std::set<std::uint64_t> visited;
  for (std::uint64_t block = number(at + 8 + lengthBytes_, lengthBytes_, what);
       block != 1 && block != none;) {
    if (block >= size || 2 * lengthBytes_ > size - block) {
      damaged(what, "its name heap's free list points at offset " + std::to_string(block) +
                        ", where a free block (" + std::to_string(2 * lengthBytes_) +
                        " bytes at least) does not fit in the heap's " + std::to_string(size) +
                        " bytes");
    }
    if (!visited.insert(block).second) {
      damaged(what, "its name heap's free list comes back to offset " + std::to_string(block));
    }
    const std::uint64_t blockAt = base_ + data + block;
    const std::uint64_t blockSize = number(blockAt + lengthBytes_, lengthBytes_, what);
    if (blockSize > size - block) {
      damaged(what, "its name heap's free block at offset " + std::to_string(block) + " claims " +
                        std::to_string(blockSize) + " bytes, past the heap's " +
                        std::to_string(size));
    }
    block = number(blockAt, lengthBytes_, what);
  }
}

void Hdf5Structure::checkMessage(const Message& m, const std::string& what,
                                 std::uint64_t* continuation, std::uint64_t* continuationLength,
                                 Storage* storage) const {
  const std::uint64_t at = m.at;
  const std::uint64_t size = m.bytes;
  const auto cutShort = [&](std::uint64_t need) {
    if (need > size) {
      damaged(what, "its message of type " + std::to_string(m.type) + " has " +
                        std::to_string(size) + " bytes, fewer than the " + std::to_string(need) +
                        " it describes");
    }
  };
  // A shared message holds a reference to the message kept elsewhere, not the message.
  if ((m.flags & 0x02) != 0 && m.type == kFilterPipelineMessage && !storage->filtersSeen) {
    storage->filtersSeen = true;
    storage->filtersShared = true;  // its filters cannot be known here
    return;
  }
  if ((m.flags & 0x02) != 0 && m.type != kDatatypeMessage) return;
  switch (m.type) {
    case kContinuationMessage:
      cutShort(offsetBytes_ + lengthBytes_);
      *continuation = number(at, offsetBytes_, what);
      *continuationLength = number(at + offsetBytes_, lengthBytes_, what);
      return;
    case kSymbolTableMessage:
      cutShort(2 * offsetBytes_);
      checkHeap(number(at + offsetBytes_, offsetBytes_, what), what);
      return;
    case kExternalFilesMessage:
      // Values kept in other files, named in a local heap libhdf5 reads unchecked.
      damaged(what, "its values are kept in external files, which this reader does not read");
    case kOldFillValueMessage: {
      cutShort(4);
      const std::uint64_t bytes = number(at, 4, what);
      cutShort(4 + bytes);
      return;
    }
    case kFillValueMessage: {
      // Version 1: allocation time, write time, defined, size (4), value; version 2: the same,
      // size and value only when defined; version 3: flags, size and value when flag 0x20. The
      // size is signed: libhdf5 copies that many bytes when it is positive.
      cutShort(2);
      const auto version = number(at, 1, what);
      std::uint64_t sizeAt = 0;
      if (version == 1) {
        sizeAt = 4;
      } else if (version == 2) {
        cutShort(4);
        if (number(at + 3, 1, what) != 0) sizeAt = 4;
      } else if (version == 3 && (number(at + 1, 1, what) & 0x20) != 0) {
        sizeAt = 2;
      }
      if (sizeAt == 0) return;
      cutShort(sizeAt + 4);
      const std::uint64_t bytes = number(at + sizeAt, 4, what);
      if (bytes < 0x80000000U) cutShort(sizeAt + 4 + bytes);
      return;
    }
    case kDatatypeMessage:
      // libhdf5 reads the first message of a type; a later one is not what it uses.
      if (storage->datatypeSeen) return;
      storage->datatypeSeen = true;
      if ((m.flags & 0x02) != 0) {
        storage->sharedDatatype = true;  // a reference to a committed datatype
        return;
      }
      cutShort(8);
      // Class and version, 3 bytes of class bits, size (4), then for a variable-length type
      // the element type: its own class bits and size (4). libhdf5 sizes its conversion buffer
      // as length x element size.
      if ((number(at, 1, what) & 0x0f) == kVariableLengthClass) {
        cutShort(16);
        storage->sequenceElementBytes = number(at + 12, 4, what);
      }
      return;
    case kLayoutMessage:
      checkLayout(m, what, storage);
      return;
    case kFilterPipelineMessage:
      checkFilters(m, what, storage);
      return;
    default:
      return;
  }
}

void Hdf5Structure::checkLayout(const Message& m, const std::string& what, Storage* storage) const {
  // Versions 3 and 4: version, class (0 compact, 1 contiguous, 2 chunked, 3 virtual), then
  // compact: data size (2), the data; contiguous: address (O), size (L); chunked, version 3:
  // rank + 1, B-tree address, 4-byte chunk sizes with the element size last; version 4: flags,
  // rank + 1, bytes per size, the sizes, the chunk index.
  const std::uint64_t at = m.at;
  const std::uint64_t size = m.bytes;
  if (size < 2) damaged(what, "its layout message is cut short");
  const auto version = number(at, 1, what);
  const auto layout = number(at + 1, 1, what);
  if (version != 3 && version != 4) {
    damaged(what, "its layout message has version " + std::to_string(version) +
                      " (this reader takes 3 and 4, what HDF5 1.6 and later write)");
  }
  if (layout > 2) {
    damaged(what, "it is a virtual dataset (layout class " + std::to_string(layout) +
                      "), which this reader does not read");
  }
  const bool first = !storage->layoutSeen;  // libhdf5 uses the first layout message
  storage->layoutSeen = true;
  if (layout == 0) {
    const std::uint64_t bytes = size >= 4 ? number(at + 2, 2, what) : 0;
    if (size < 4 || bytes > size - 4) {
      damaged(what, "its compact data claims " + std::to_string(bytes) + " bytes in a message of " +
                        std::to_string(size));
    }
    if (first) {
      storage->known = true;
      storage->at = at + 4;
      storage->bytes = bytes;
    }
    return;
  }
  if (layout == 1) {
    if (size < 2 + offsetBytes_ + lengthBytes_) damaged(what, "its layout message is cut short");
    const auto address = number(at + 2, offsetBytes_, what);
    const auto bytes = number(at + 2 + offsetBytes_, lengthBytes_, what);
    if (!undefined(address) && !inside(address, bytes)) {
      claimsOutside(what, "its data", bytes, address);
    }
    if (first && !undefined(address)) {
      storage->known = true;
      storage->at = base_ + address;
      storage->bytes = bytes;
    }
    return;
  }
  std::uint64_t dims = 0;
  std::uint64_t width = 4;
  std::uint64_t sizes = 0;
  if (version == 3) {
    dims = number(at + 2, 1, what);
    sizes = at + 3 + offsetBytes_;
  } else {
    dims = number(at + 3, 1, what);
    width = number(at + 4, 1, what);
    sizes = at + 5;
    if (width == 0 || width > 8) {
      damaged(what, "its chunk sizes have " + std::to_string(width) + " bytes each");
    }
  }
  if (sizes + dims * width > at + size) damaged(what, "its layout message is cut short");
  std::uint64_t bytes = 1;
  for (std::uint64_t i = 0; i < dims; ++i) {
    const std::uint64_t d = number(sizes + i * width, width, what);
    if (d == 0) damaged(what, "its chunks have a dimension of 0");  // libhdf5 refuses it too
    if (bytes > kMaxArrayBytes / d) {
      damaged(what, "its chunks are larger than this reader accepts (" +
                        std::to_string(kMaxArrayBytes) + " bytes)");
    }
    bytes *= d;
  }
  // Version 4 indexes its chunks in one of five structures (a single chunk, implicit, fixed or
  // extensible arrays, version 2 B-trees), written only with libver "latest"; they are left to
  // libhdf5. Version 3 (h5py's default, ACRONYM's files) uses a version 1 B-tree.
  if (version == 3 && first) {
    storage->chunked = true;
    storage->chunkTree = number(at + 3, offsetBytes_, what);
    storage->chunkDims = dims;
    storage->chunkBytes = bytes;
  }
}

void Hdf5Structure::checkFilters(const Message& m, const std::string& what,
                                 Storage* storage) const {
  if (storage->filtersSeen) return;  // libhdf5 uses the first pipeline message
  storage->filtersSeen = true;
  // Version 1: version, count, 6 reserved bytes, then per filter: id (2), name length (2, a
  // multiple of 8), flags (2), client values (2), the name, the values (4 bytes each), 4 bytes
  // of padding after an odd number of values. Version 2: id (2), name length (2) only for an id
  // of 256 or more, flags (2), values (2), the name unpadded, the values.
  const std::uint64_t end = m.at + m.bytes;
  const auto need = [&](std::uint64_t pos, std::uint64_t bytes) {
    if (pos > end || bytes > end - pos) damaged(what, "its filter pipeline message is cut short");
  };
  need(m.at, 2);
  const auto version = number(m.at, 1, what);
  const auto count = number(m.at + 1, 1, what);
  if (version != 1 && version != 2) {
    damaged(what, "its filter pipeline message has version " + std::to_string(version));
  }
  std::uint64_t pos = m.at + (version == 1 ? 8 : 2);
  for (std::uint64_t i = 0; i < count; ++i) {
    need(pos, 2);
    const auto id = static_cast<unsigned>(number(pos, 2, what));
    std::uint64_t nameBytes = 0;
    pos += 2;
    if (version == 1 || id >= 256) {
      need(pos, 2);
      nameBytes = number(pos, 2, what);
      pos += 2;
    }
    need(pos, 4);
    const std::uint64_t values = number(pos + 2, 2, what);
    pos += 4 + nameBytes + 4 * values + (version == 1 && values % 2 == 1 ? 4 : 0);
    need(pos, 0);
    storage->filters.push_back(id);
  }
}

std::uint64_t Hdf5Structure::unfilteredBytes(std::string_view data, std::uint64_t mask,
                                             const Storage& storage, const std::string& what,
                                             std::uint64_t address) const {
  // Reading undoes the filters last first; bit i of the key's mask: filter i was skipped.
  std::string inflated;
  std::uint64_t bytes = data.size();
  for (std::size_t i = storage.filters.size(); i-- > 0;) {
    if (i < 64 && ((mask >> i) & 1U) != 0) continue;
    switch (storage.filters[i]) {
      case kFletcher32Filter:  // a 4-byte checksum after the data
        if (bytes < 4)
          damaged(what, "a chunk at byte " + byteText(address) + " lacks its checksum");
        bytes -= 4;
        data = data.substr(0, bytes);
        break;
      case kDeflateFilter: {
        // At most the chunk's bytes plus the checksums of the filters still to undo.
        const std::uint64_t limit = storage.chunkBytes + 4 * storage.filters.size();
        inflated = inflate(data, limit, [&](const std::string& why) {
          damaged(what, "a chunk at byte " + byteText(address) + " " + why);
        });
        data = inflated;
        bytes = inflated.size();
        break;
      }
      default:  // shuffle keeps the size
        break;
    }
  }
  return bytes;
}

void Hdf5Structure::checkChunkTree(const Storage& storage, const std::string& what) const {
  const std::uint64_t address = storage.chunkTree;
  const std::uint64_t dims = storage.chunkDims;
  if (storage.filtersShared) {
    unsupported(what, "its filter pipeline is a shared message, which this reader does not read");
  }
  for (const unsigned id : storage.filters) {
    if (id < kDeflateFilter || id > kFletcher32Filter) {
      unsupported(what, "its chunks pass through HDF5 filter " + std::to_string(id) +
                            ", which this reader does not take (it takes deflate, shuffle and "
                            "fletcher32)");
    }
  }
  if (undefined(address)) return;  // no chunk written yet: libhdf5 reads the fill value
  // A node: "TREE", type (1: chunks), level, entries used (2), left and right siblings, then
  // keys and children alternating, one key more than children. A key: the chunk's size in the
  // file (4; after its filters), the filter mask (4) and `dims` 8-byte offsets. A child: a node
  // one level down, or at level 0 the chunk's address.
  const std::uint64_t keyBytes = 8 + 8 * dims;
  std::set<std::uint64_t> visited;
  std::set<std::uint64_t> chunks;
  std::uint64_t unfolded = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> pending{{address, kMaxTreeLevel + 1}};
  while (!pending.empty()) {
    const auto [node, expectedLevel] = pending.back();
    pending.pop_back();
    const std::string thing = "its chunk index node";
    if (!inside(node, 8 + 2 * offsetBytes_)) outside(what, thing, node);
    if (!visited.insert(node).second) {
      damaged(what, thing + " at byte " + byteText(node) +
                        " is reached twice: the chunk index points back into itself");
    }
    if (visited.size() > kMaxTreeNodes) {
      damaged(what, "its chunk index has more than " + std::to_string(kMaxTreeNodes) + " nodes");
    }
    const std::uint64_t at = base_ + node;
    if (image_.substr(at, 4) != "TREE" || number(at + 4, 1, what) != 1) {
      damaged(what, thing + " at byte " + byteText(node) +
                        " is not a chunk B-tree node (no \"TREE\" signature of type 1)");
    }
    const std::uint64_t level = number(at + 5, 1, what);
    if (level > kMaxTreeLevel || (expectedLevel <= kMaxTreeLevel && level != expectedLevel)) {
      damaged(what, thing + " at byte " + byteText(node) + " has level " + std::to_string(level) +
                        (expectedLevel <= kMaxTreeLevel
                             ? ", below a node of level " + std::to_string(expectedLevel + 1)
                             : " (at most " + std::to_string(kMaxTreeLevel) + ")"));
    }
    const std::uint64_t entries = number(at + 6, 2, what);
    const std::uint64_t bytes =
        8 + 2 * offsetBytes_ + (entries + 1) * keyBytes + entries * offsetBytes_;
    if (!inside(node, bytes)) claimsOutside(what, thing, bytes, node);
    std::uint64_t key = at + 8 + 2 * offsetBytes_;
    for (std::uint64_t i = 0; i < entries; ++i, key += keyBytes + offsetBytes_) {
      const std::uint64_t child = number(key + keyBytes, offsetBytes_, what);
      if (level > 0) {
        pending.emplace_back(child, level - 1);
        continue;
      }
      // libhdf5 allocates a buffer of the key's size and reads the chunk into it, runs the
      // filters backwards and copies one chunk's bytes out of what they give: fewer (a short
      // deflate stream, a damaged chunk size) were read past the buffer's end.
      const std::uint64_t size = number(key, 4, what);
      if (!inside(child, size)) claimsOutside(what, "a chunk", size, child);
      if (!chunks.insert(child).second) {
        damaged(what, "a chunk at byte " + byteText(child) + " is listed twice in its chunk index");
      }
      if (chunks.size() > kMaxHdf5Chunks) {
        damaged(what,
                "its chunk index lists more than " + std::to_string(kMaxHdf5Chunks) + " chunks");
      }
      const std::uint64_t mask = number(key + 4, 4, what);
      unfolded += storage.chunkBytes;
      if (unfolded > kMaxUnfilteredBytes) {
        damaged(what,
                "its chunks add up to more than " + std::to_string(kMaxUnfilteredBytes) + " bytes");
      }
      const std::uint64_t got =
          unfilteredBytes(image_.substr(base_ + child, size), mask, storage, what, child);
      if (got != storage.chunkBytes) {
        damaged(what, "a chunk at byte " + byteText(child) + " gives " + std::to_string(got) +
                          " bytes" + (storage.filters.empty() ? "" : " through its filters") +
                          ", but the dataset's chunks have " + std::to_string(storage.chunkBytes));
      }
    }
  }
}

Hdf5Structure::Storage Hdf5Structure::checkObject(std::uint64_t address,
                                                  const std::string& what) const {
  Storage storage;
  if (!found_) return storage;
  if (!inside(address, 16)) {
    outside(what, "its object header", address);
  }
  const std::uint64_t at = base_ + address;
  bool v2 = false;
  std::uint64_t messageHeader = 8;
  std::uint64_t start = 0;
  std::uint64_t size = 0;
  if (image_[at] == 1) {
    // Version 1: version, reserved, message count (2), reference count (4), chunk size (4),
    // 4 bytes of alignment, then the messages.
    size = number(at + 8, 4, what);
    start = address + 16;
  } else if (image_.substr(at, 4) == "OHDR" && image_[at + 4] == 2) {
    // Version 2: "OHDR", version, flags, [4 times], [2 attribute limits], chunk size (1, 2, 4
    // or 8 bytes by flags bits 0-1), the messages, a checksum.
    v2 = true;
    const auto flags = number(at + 5, 1, what);
    std::uint64_t pos = 6 + ((flags & 0x20) != 0 ? 16 : 0) + ((flags & 0x10) != 0 ? 4 : 0);
    const std::size_t width = std::size_t{1} << (flags & 3);
    size = number(at + pos, width, what);
    start = address + pos + width;
    messageHeader = (flags & 0x04) != 0 ? 6 : 4;
  } else {
    return storage;  // not an object header this reader knows: libhdf5 refuses it
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks{{start, size}};
  std::set<std::uint64_t> seen{start};
  // The chunks of a valid header are disjoint parts of the file: more bytes than the file has
  // means they overlap (a damaged header could otherwise make this walk the file many times).
  std::uint64_t walked = 0;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    const auto [chunk, length] = chunks[c];
    if (!inside(chunk, length)) {
      claimsOutside(what, "its object header", length, chunk);
    }
    walked += length;
    if (walked > image_.size()) damaged(what, "the chunks of its object header overlap");
    std::uint64_t pos = base_ + chunk;
    const std::uint64_t end = base_ + chunk + length;
    while (pos + messageHeader <= end) {
      Message m;
      m.type = static_cast<unsigned>(v2 ? number(pos, 1, what) : number(pos, 2, what));
      m.bytes = number(pos + (v2 ? 1 : 2), 2, what);
      m.flags = static_cast<unsigned>(number(pos + (v2 ? 3 : 4), 1, what));
      m.at = pos + messageHeader;
      if (m.bytes > end - m.at) break;  // libhdf5 refuses the header
      std::uint64_t next = 0;
      std::uint64_t nextLength = 0;
      checkMessage(m, what, &next, &nextLength, &storage);
      if (nextLength != 0 || next != 0) {
        if (chunks.size() >= kMaxHeaderChunks)
          damaged(what, "its object header has too many chunks");
        // A version 2 continuation chunk: "OCHK", the messages, a checksum.
        if (v2 && nextLength < 8) damaged(what, "a continuation chunk of its header is too short");
        if (!inside(next, nextLength)) {
          damaged(what, "a continuation of its object header (" + std::to_string(nextLength) +
                            " bytes at byte " + byteText(next) + ") lies outside " + fileText());
        }
        const std::uint64_t first = v2 ? next + 4 : next;
        if (seen.insert(first).second) chunks.emplace_back(first, v2 ? nextLength - 8 : nextLength);
      }
      pos = m.at + m.bytes;
    }
  }
  if (storage.chunked) checkChunkTree(storage, what);
  return storage;
}

void Hdf5Structure::checkVariableLengthString(const Storage& storage,
                                              const std::string& what) const {
  if (!found_) return;
  if (storage.sharedDatatype) {
    damaged(what,
            "its string's type is a committed (shared) datatype, which this reader does "
            "not read");
  }
  // A string's characters are bytes: libhdf5 allocates the string's length times this (a
  // damaged file asked for 2.7 GB this way).
  if (storage.sequenceElementBytes != 1) {
    damaged(what, "its variable-length string has characters of " +
                      std::to_string(storage.sequenceElementBytes) + " bytes (expected 1)");
  }
  if (!storage.known) return;
  // The stored value: the string's length (4), the collection's address (O), the object's index
  // in it (4).
  if (storage.bytes < 8 + offsetBytes_) {
    damaged(what, "its string reference has " + std::to_string(storage.bytes) + " bytes");
  }
  const std::uint64_t length = number(storage.at, 4, what);
  const std::uint64_t collection = number(storage.at + 4, offsetBytes_, what);
  const std::uint64_t index = number(storage.at + 4 + offsetBytes_, 4, what);
  // libhdf5 reads nothing for a collection address of 0 (a null string), whatever the length.
  if (collection == 0) return;
  // The collection: "GCOL", version 1, 3 reserved, its size (L) including this header, then the
  // objects: index (2), reference count (2), reserved (4), size (L), the data padded to 8 bytes;
  // index 0 is the free space that ends it.
  const std::uint64_t headerBytes = 8 + lengthBytes_;
  if (!inside(collection, headerBytes)) {
    outside(what, "its string's global heap", collection);
  }
  const std::uint64_t at = base_ + collection;
  if (image_.substr(at, 4) != "GCOL" || image_[at + 4] != 1) {
    damaged(what, "no global heap (version 1) at byte " + std::to_string(collection) +
                      ", where its string points");
  }
  const std::uint64_t size = number(at + 8, lengthBytes_, what);
  if (size < headerBytes || !inside(collection, size)) {
    claimsOutside(what, "its string's global heap", size, collection);
  }
  // Walked as libhdf5 walks it when it loads the collection: an object of index 0 (the free
  // space) advances by its size, header included; any other by its header and its data padded to
  // 8 bytes; less room than an object header ends the walk. A step of 0 bytes made libhdf5 loop
  // for ever, one past the collection's end made it copy past its buffer.
  const std::uint64_t end = at + size;
  const std::uint64_t objectHeader = 8 + lengthBytes_;
  bool found = false;
  std::uint64_t objectBytes = 0;
  for (std::uint64_t pos = at + headerBytes; end - pos >= objectHeader;) {
    const std::uint64_t id = number(pos, 2, what);
    const std::uint64_t bytes = number(pos + 8, lengthBytes_, what);
    const std::uint64_t room = end - pos;
    const std::uint64_t step =
        id == 0 ? bytes : (bytes > room ? room + 1 : objectHeader + (bytes + 7) / 8 * 8);
    if (step == 0 || step > room) {
      damaged(what, (id == 0 ? std::string("the free space") : "object " + std::to_string(id)) +
                        " of its string's global heap claims " + std::to_string(bytes) +
                        " bytes, " + (step == 0 ? "none" : "more than the heap holds"));
    }
    if (id == index && id != 0) {
      found = true;  // libhdf5 keeps the last object of an index
      objectBytes = bytes;
    }
    pos += step;
  }
  // libhdf5 sizes its buffer by the length and copies the object at the object's size.
  if (found && objectBytes != length) {
    damaged(what, "its string has " + std::to_string(length) + " bytes, its global heap object " +
                      std::to_string(index) + " holds " + std::to_string(objectBytes));
  }
  if (!found) {
    damaged(what, "its string's global heap has no object " + std::to_string(index));
  }
}

}  // namespace visgrab::importers::detail
