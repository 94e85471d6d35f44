// The HDF5 metadata checks made before libhdf5 reads a file (detail::Hdf5Structure,
// docs/fuzzing.md item 7): on images built byte by byte here from the HDF5 File Format
// Specification (superblocks 0 and 2, object headers 1 and 2, the symbol table, continuation and
// layout messages, the local heap), on files written by libhdf5 and damaged by hand the way the
// fuzz stage found, and on every input the fuzz stage found (fuzz/regressions/hdf5).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "import_checks.hpp"
#include "support/test_support.hpp"
#include "test_files.hpp"
#include "visgrab/importers/hdf5_file.hpp"
#include "visgrab/importers/hdf5_structure.hpp"
#include "visgrab/importers/npy.hpp"

namespace visgrab::importers {
namespace {

using detail::Hdf5Structure;
using test::errorOf;

constexpr std::uint64_t kUndefined = ~std::uint64_t{0};

// Little-endian bytes, appended.
struct Bytes {
  std::string s;
  Bytes& u(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) s.push_back(i < 8 ? static_cast<char>((v >> (8 * i)) & 0xff) : 0);
    return *this;
  }
  Bytes& text(const std::string& t) {
    s += t;
    return *this;
  }
  Bytes& pad(std::size_t to) {
    s.resize(to, '\0');
    return *this;
  }
};

const std::string kSignature("\x89HDF\r\n\x1a\n", 8);

// A version 0 superblock (8-byte offsets and lengths) whose root symbol table entry points at
// byte 96, where the root's version 1 object header follows with `messages` (each: type, data).
std::string version0File(const std::vector<std::pair<unsigned, std::string>>& messages,
                         std::size_t total = 1024) {
  Bytes b;
  b.text(kSignature).u(0, 1).u(0, 1).u(0, 1).u(0, 1).u(0, 1).u(8, 1).u(8, 1).u(0, 1);
  b.u(4, 2).u(16, 2).u(0, 4);                               // group K values, flags: byte 24
  b.u(0, 8).u(kUndefined, 8).u(total, 8).u(kUndefined, 8);  // base, free space, EOF, driver
  b.u(0, 8).u(96, 8).u(0, 4).u(0, 4).u(0, 16);              // root entry: header at 96
  EXPECT_EQ(b.s.size(), 96U);
  std::string body;
  for (const auto& [type, data] : messages) {
    Bytes m;
    m.u(type, 2).u(data.size(), 2).u(0, 1).u(0, 3).text(data);
    body += m.s;
  }
  b.u(1, 1).u(0, 1).u(messages.size(), 2).u(1, 4).u(body.size(), 4).u(0, 4).text(body);
  return b.pad(total).s;
}

std::string symbolTable(std::uint64_t heap) { return Bytes().u(300, 8).u(heap, 8).s; }

// A local heap at `at` in `file`: "HEAP", version 0, data size, free list offset, data address.
void putHeap(std::string& file, std::size_t at, std::uint64_t size, std::uint64_t data) {
  const std::string heap = Bytes().text("HEAP").u(0, 4).u(size, 8).u(kUndefined, 8).u(data, 8).s;
  file.replace(at, heap.size(), heap);
}

std::string errorOfRoot(const std::string& file) {
  return errorOf([&] { Hdf5Structure(file, "hand.h5").checkRoot(); });
}

TEST(Hdf5Structure, ASymbolTableGroupsNameHeapMustLieInsideTheFile) {
  std::string file = version0File({{0x11, symbolTable(512)}});
  putHeap(file, 512, 88, 544);
  EXPECT_EQ(errorOfRoot(file), "");  // 88 bytes at 544 end at 632 of 1024
  putHeap(file, 512, 480, 544);
  EXPECT_EQ(errorOfRoot(file), "");  // ends exactly at the file's end
  putHeap(file, 512, 481, 544);
  EXPECT_EQ(errorOfRoot(file),
            "hand.h5: damaged HDF5 file: the root group: its name heap claims 481 bytes at byte "
            "544, outside the file of 1024 bytes");
  // The fuzz stage's findings: a claimed size of 2^48 (libhdf5 allocated it before reading) and
  // an undefined data address (libhdf5 read from a null pointer).
  putHeap(file, 512, std::uint64_t{1} << 48, 544);
  EXPECT_NE(errorOfRoot(file).find("claims 281474976710656 bytes at byte 544"), std::string::npos);
  putHeap(file, 512, 88, kUndefined);
  EXPECT_NE(errorOfRoot(file).find("claims 88 bytes at byte (undefined)"), std::string::npos);
  // A symbol table that points where no heap is, or outside the file.
  EXPECT_NE(errorOfRoot(version0File({{0x11, symbolTable(600)}})).find("no name heap"),
            std::string::npos);
  EXPECT_NE(errorOfRoot(version0File({{0x11, symbolTable(5000)}}))
                .find("its name heap (at byte 5000) lies outside the file of 1024 bytes"),
            std::string::npos);
}

TEST(Hdf5Structure, ContinuationChunksMustLieInsideTheFileAndAreFollowed) {
  const auto continuation = [](std::uint64_t at, std::uint64_t length) {
    return Bytes().u(at, 8).u(length, 8).s;
  };
  EXPECT_EQ(errorOfRoot(version0File({{0x10, continuation(100000, 512)}})),
            "hand.h5: damaged HDF5 file: the root group: a continuation of its object header "
            "(512 bytes at byte 100000) lies outside the file of 1024 bytes");
  EXPECT_NE(errorOfRoot(version0File({{0x10, continuation(512, 3539992592)}}))
                .find("(3539992592 bytes at byte 512)"),
            std::string::npos);
  // A chunk inside the file is read: its symbol table message is checked too.
  std::string file = version0File({{0x10, continuation(512, 24)}});
  const std::string stab = Bytes().u(0x11, 2).u(16, 2).u(0, 4).u(300, 8).u(700, 8).s;
  file.replace(512, stab.size(), stab);
  EXPECT_NE(errorOfRoot(file).find("no name heap (local heap, version 0) at byte 700"),
            std::string::npos);
  putHeap(file, 700, 16, 740);
  EXPECT_EQ(errorOfRoot(file), "");
  // A continuation that points back at itself ends (libhdf5 refuses the header itself).
  std::string loop = version0File({{0x10, continuation(512, 24)}});
  const std::string back = Bytes().u(0x10, 2).u(16, 2).u(0, 4).u(512, 8).u(24, 8).s;
  loop.replace(512, back.size(), back);
  EXPECT_EQ(errorOfRoot(loop), "");
}

TEST(Hdf5Structure, LayoutMessagesMustFitTheirDataAndChunks) {
  const auto layout = [](unsigned cls, const std::string& rest) {
    return Bytes().u(3, 1).u(cls, 1).text(rest).s;
  };
  // Compact: 8 bytes of data in the message, then one claiming 4000.
  EXPECT_EQ(errorOfRoot(version0File({{0x08, layout(0, Bytes().u(8, 2).u(7, 8).s)}})), "");
  EXPECT_NE(errorOfRoot(version0File({{0x08, layout(0, Bytes().u(4000, 2).u(7, 8).s)}}))
                .find("its compact data claims 4000 bytes in a message of 12"),
            std::string::npos);
  // Contiguous: 124 bytes at 900 end at 1024, 125 past it; an undefined address is "not
  // written yet".
  EXPECT_EQ(errorOfRoot(version0File({{0x08, layout(1, Bytes().u(900, 8).u(124, 8).s)}})), "");
  EXPECT_NE(errorOfRoot(version0File({{0x08, layout(1, Bytes().u(900, 8).u(125, 8).s)}}))
                .find("its data claims 125 bytes at byte 900, outside the file of 1024 bytes"),
            std::string::npos);
  EXPECT_EQ(errorOfRoot(version0File({{0x08, layout(1, Bytes().u(kUndefined, 8).u(100, 8).s)}})),
            "");
  // Chunked (version 3): rank 2 + element size 8: 1000 x 1000 x 8 bytes fits, 2^16 x 2^16 x 8
  // (32 GiB) does not. Its chunk index (B-tree) address undefined: no chunk written yet; at
  // byte 800, where no B-tree node is, refused (libhdf5's own trees:
  // AChunkIndexMustHoldItsChunksInsideTheFile).
  const auto chunked = [&](std::uint64_t rows, std::uint64_t cols,
                           std::uint64_t tree = kUndefined) {
    return layout(2, Bytes().u(3, 1).u(tree, 8).u(rows, 4).u(cols, 4).u(8, 4).s);
  };
  EXPECT_EQ(errorOfRoot(version0File({{0x08, chunked(1000, 1000)}})), "");
  EXPECT_HAS(errorOfRoot(version0File({{0x08, chunked(1000, 1000, 800)}})),
             "its chunk index node at byte 800 is not a chunk B-tree node");
  EXPECT_NE(errorOfRoot(version0File({{0x08, chunked(65536, 65536)}}))
                .find("its chunks are larger than this reader accepts (" +
                      std::to_string(kMaxArrayBytes) + " bytes)"),
            std::string::npos);
  // A compact message too short to hold its size, layout versions before 3 (libhdf5 1.10 still
  // reads them, with a 4-byte compact size it does not bound) and virtual datasets (their source
  // list lives in an unchecked global heap) are refused.
  EXPECT_NE(errorOfRoot(version0File({{0x08, layout(0, "")}}))
                .find("its compact data claims 0 bytes in a message of 2"),
            std::string::npos);
  EXPECT_NE(errorOfRoot(version0File({{0x08, Bytes().u(1, 1).u(1, 1).u(0, 14).s}}))
                .find("its layout message has version 1"),
            std::string::npos);
  EXPECT_NE(errorOfRoot(version0File({{0x08, layout(3, Bytes().u(0, 16).s)}}))
                .find("it is a virtual dataset"),
            std::string::npos);
  // libhdf5 uses the first layout message of a header: so does the check.
  const auto twice = version0File({{0x08, layout(1, Bytes().u(200, 8).u(24, 8).s)},
                                   {0x08, layout(1, Bytes().u(300, 8).u(48, 8).s)}});
  const auto storage = Hdf5Structure(twice, "hand.h5").checkObject(96, "'x'");
  EXPECT_TRUE(storage.known);
  EXPECT_EQ(storage.at, 200U);
  EXPECT_EQ(storage.bytes, 24U);
}

// A version 0 superblock's driver information block (its address the fourth after the base;
// version, 3 reserved bytes, size (4), driver name (8), the information): libhdf5 allocated the
// 0xFFFFFFFF bytes it claimed (fuzz/regressions/hdf5/driver-info-4GB).
TEST(Hdf5Structure, ADriverInformationBlockMustLieInsideTheFile) {
  std::string file = version0File({});
  file.replace(48, 8, Bytes().u(512, 8).s);  // the driver block's address, byte 24 + 3 x 8
  file.replace(512, 16, Bytes().u(0, 4).u(8, 4).text("NCSAmult").s);
  EXPECT_EQ(errorOfRoot(file), "");
  file.replace(516, 4, Bytes().u(0xFFFFFFFF, 4).s);
  EXPECT_EQ(errorOfRoot(file),
            "hand.h5: damaged HDF5 file: the superblock: its driver information block claims "
            "4294967311 bytes at byte 512, outside the file of 1024 bytes");
  file.replace(48, 8, Bytes().u(1020, 8).s);
  EXPECT_EQ(errorOfRoot(file),
            "hand.h5: damaged HDF5 file: the superblock: its driver information block (at byte "
            "1020) lies outside the file of 1024 bytes");
}

TEST(Hdf5Structure, FillValuesMustFitTheirMessageAndExternalStorageIsRefused) {
  // Fill value message version 3: flags 0x20 (a value is defined), size (4), the value.
  const auto fill = [](std::uint64_t bytes, std::size_t held) {
    return Bytes().u(3, 1).u(0x20, 1).u(bytes, 4).pad(6 + held).s;
  };
  EXPECT_EQ(errorOfRoot(version0File({{0x05, fill(8, 8)}})), "");
  EXPECT_NE(errorOfRoot(version0File({{0x05, fill(1000, 8)}}))
                .find("its message of type 5 has 14 bytes, fewer than the 1006 it describes"),
            std::string::npos);
  // Version 2 with no value defined holds no size; the old fill value message (4) one.
  EXPECT_EQ(errorOfRoot(version0File({{0x05, Bytes().u(2, 1).u(2, 1).u(2, 1).u(0, 1).s}})), "");
  EXPECT_NE(errorOfRoot(version0File({{0x04, Bytes().u(4000, 4).u(0, 4).s}})).find("fewer than"),
            std::string::npos);
  EXPECT_NE(errorOfRoot(version0File({{0x07, Bytes().u(1, 1).u(0, 23).s}}))
                .find("its values are kept in external files"),
            std::string::npos);
}

TEST(Hdf5Structure, VersionTwoHeadersAndSuperblocksAndAUserBlock) {
  // Superblock version 2 at byte 512 (after a user block): offsets and lengths of 8 bytes; the
  // root's "OHDR" header at address 100, i.e. byte 612.
  Bytes b;
  b.pad(512).text(kSignature).u(2, 1).u(8, 1).u(8, 1).u(0, 1);
  b.u(0, 8).u(kUndefined, 8).u(2048, 8).u(100, 8).u(0, 4);
  b.pad(612);
  // "OHDR", version 2, flags 0 (1-byte chunk size), size 20: one continuation message (type,
  // size 2, flags) of 16 bytes.
  b.text("OHDR").u(2, 1).u(0, 1).u(20, 1).u(0x10, 1).u(16, 2).u(0, 1).u(9000, 8).u(64, 8);
  b.pad(2048);
  EXPECT_NE(errorOfRoot(b.s).find("a continuation of its object header (64 bytes at byte 9000)"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              Hdf5Structure(b.s, "hand.h5").checkObject(5000, "'x'");
            }).find("'x': its object header (at byte 5000) lies outside the file of 2048 bytes"),
            std::string::npos);
  // Flags 0x24 (creation order kept: 6-byte message headers; times: 16 more bytes before the
  // chunk size), and a continuation into an "OCHK" chunk whose symbol table message points at
  // byte 1500, where no heap is: the walk found the chunk's messages where they are.
  Bytes t;
  t.pad(512).text(kSignature).u(2, 1).u(8, 1).u(8, 1).u(0, 1);
  t.u(0, 8).u(kUndefined, 8).u(2048, 8).u(100, 8).u(0, 4);
  t.pad(612);
  t.text("OHDR").u(2, 1).u(0x24, 1).u(0, 16).u(22, 1);
  t.u(0x10, 1).u(16, 2).u(0, 1).u(0, 2).u(1000, 8).u(4 + 6 + 16 + 4, 8).u(0, 4);
  t.pad(512 + 1000).text("OCHK").u(0x11, 1).u(16, 2).u(0, 1).u(0, 2).u(300, 8).u(1500, 8);
  t.pad(2048);
  EXPECT_NE(errorOfRoot(t.s).find("no name heap (local heap, version 0) at byte 1500"),
            std::string::npos);
  // Not an HDF5 file at all: nothing to check (libhdf5 says what it is not).
  EXPECT_FALSE(Hdf5Structure("plain text", "t").found());
}

// A file libhdf5 wrote, damaged by hand as the fuzz stage damaged its seed: the root group's name
// heap claims 2^48 bytes, then its data address is undefined. Both are refused before libhdf5
// reads the heap (it asked for 2^48 bytes, then crashed, on these).
TEST(Hdf5Structure, DamagedNameHeapsOfARealFileAreRefusedBeforeLibhdf5ReadsThem) {
  test::TempDir dir;
  const auto path = dir.path() / "t.h5";
  test::writeHdf5(path, {{"grasps/transforms", {1, 2}, {1, 2}}});
  const std::string good = readFileBytes(path, 1 << 20);
  EXPECT_EQ(Hdf5File::fromBytes(good, "t.h5").numbers("grasps/transforms").values,
            (std::vector<double>{1, 2}));
  const std::size_t heap = good.find("HEAP");
  ASSERT_NE(heap, std::string::npos);
  for (const auto& [offset, value] : {std::pair<std::size_t, std::uint64_t>{8, 1ULL << 48},
                                      std::pair<std::size_t, std::uint64_t>{24, kUndefined}}) {
    std::string bad = good;
    bad.replace(heap + offset, 8, Bytes().u(value, 8).s);
    const std::string error =
        errorOf([&] { Hdf5File::fromBytes(bad, "t.h5").numbers("grasps/transforms"); });
    EXPECT_EQ(error.rfind("t.h5: damaged HDF5 file: ", 0), 0U) << error;
    EXPECT_NE(error.find("its name heap claims"), std::string::npos) << error;
  }
  // The heap's free list (head at byte 16 of the heap; a free block: next offset, size) made to
  // come back to itself, as the fuzz stage's name-heap-free-list-loop (libhdf5 allocated a list
  // entry per visit until memory ran out).
  const auto number = [&](std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) {
      v |= std::uint64_t{static_cast<unsigned char>(good[at + i])} << (8 * i);
    }
    return v;
  };
  const std::uint64_t head = number(heap + 16);
  const std::uint64_t data = number(heap + 24);
  ASSERT_LT(head, number(heap + 8));  // the heap has a free block
  std::string looped = good;
  looped.replace(data + head, 8, Bytes().u(head, 8).s);
  EXPECT_HAS(errorOf([&] { Hdf5File::fromBytes(looped, "t.h5").numbers("grasps/transforms"); }),
             "t.h5: damaged HDF5 file: the root group: its name heap's free list comes back to "
             "offset " +
                 std::to_string(head));
}

// A chunked dataset (ACRONYM's are, deflated, h5py's default layout version 3) indexes its chunks
// in a version 1 B-tree and passes them through a filter pipeline: one libhdf5 wrote reads; a
// chunk whose filters give other than one chunk's bytes, a damaged deflate stream and a filter
// this reader does not take are refused; a key claiming 0xF0000000 bytes for a chunk
// (libhdf5 1.10.8 allocated that much to read it: "memory allocation failed for raw data chunk"
// under a 4 GB limit), a node without its signature, a level beyond any tree this reader takes
// and a node that points back at itself are refused before libhdf5 reads them.
TEST(Hdf5Structure, AChunkIndexMustHoldItsChunksInsideTheFile) {
  test::TempDir dir;
  const auto path = dir.path() / "c.h5";
  std::vector<double> values(16);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>(i);
  test::writeHdf5(path, {{"grasps/transforms", {8, 2}, values, false, false, "", {2, 2}, true}});
  const std::string good = readFileBytes(path, 1 << 20);
  EXPECT_EQ(Hdf5File::fromBytes(good, "c.h5").numbers("grasps/transforms").values, values);
  // The chunk tree's node (type 1; the root group's symbol table is a tree of type 0): "TREE",
  // type, level, entries used (2), two 8-byte siblings, then key 0 (size 4, filter mask 4, three
  // 8-byte offsets: two dimensions and the element's) and child 0 (8), key 1, ...
  const std::size_t node = good.find(std::string("TREE\x01", 5));
  ASSERT_NE(node, std::string::npos);
  ASSERT_EQ(good[node + 5], 0);  // level 0: its children are the chunks
  ASSERT_EQ(good[node + 6], 4);  // 8 x 2 values in chunks of 2 x 2
  const auto errorOfDamaged = [&](const std::vector<std::pair<std::size_t, std::string>>& edits) {
    std::string bad = good;
    for (const auto& [at, bytes] : edits) bad.replace(node + at, bytes.size(), bytes);
    return errorOf([&] { Hdf5File::fromBytes(bad, "c.h5").numbers("grasps/transforms"); });
  };
  EXPECT_HAS(errorOfDamaged({{24, Bytes().u(0xF0000000, 4).s}}),
             "c.h5: damaged HDF5 file: 'grasps/transforms': a chunk claims 4026531840 bytes at "
             "byte ");
  EXPECT_HAS(errorOfDamaged({{0, "TRXX"}}),
             "'grasps/transforms': its chunk index node at byte " + std::to_string(node) +
                 " is not a chunk B-tree node (no \"TREE\" signature of type 1)");
  EXPECT_HAS(errorOfDamaged({{5, Bytes().u(40, 1).s}}),
             "its chunk index node at byte " + std::to_string(node) + " has level 40 (at most 32)");
  // Level 1 with one entry whose child is the node itself.
  EXPECT_HAS(errorOfDamaged({{5, Bytes().u(1, 1).u(1, 2).s}, {24 + 32, Bytes().u(node, 8).s}}),
             "its chunk index node at byte " + std::to_string(node) +
                 " is reached twice: the chunk index points back into itself");
  // Entries the node has no room for: 24 + 60,001 keys of 32 bytes + 60,000 children of 8.
  EXPECT_HAS(errorOfDamaged({{6, Bytes().u(60000, 2).s}}),
             "its chunk index node claims 2400056 bytes at byte " + std::to_string(node));
  // libhdf5 copies one chunk's bytes (2 x 2 x 8 = 32) out of what the filters give; fewer were
  // read past the filter's buffer (the fuzz stage's chunk-overread-* inputs). Chunk 0's key
  // claiming only its 2-byte zlib header inflates to nothing; a zlib header made 0 0 does not
  // inflate at all.
  std::uint64_t chunk0 = 0;
  for (int i = 0; i < 8; ++i) {
    chunk0 |= std::uint64_t{static_cast<unsigned char>(good[node + 56 + i])} << (8 * i);
  }
  EXPECT_HAS(errorOfDamaged({{24, Bytes().u(2, 4).s}}),
             "'grasps/transforms': a chunk at byte " + std::to_string(chunk0) +
                 " gives 0 bytes through its filters, but the dataset's chunks have 32");
  EXPECT_HAS(errorOfDamaged({{chunk0 - node, Bytes().u(0, 2).s}}),
             "a chunk at byte " + std::to_string(chunk0) + " does not inflate (zlib: ");
  // The filter pipeline (version 1): filter id, name length, flags, values, "deflate\0". A
  // filter this reader cannot undo here (4: szip) is refused as such, not as damage.
  const std::size_t deflate = good.find("deflate");
  ASSERT_NE(deflate, std::string::npos);
  ASSERT_EQ(good[deflate - 8], 1);
  const std::string szip = errorOfDamaged({{deflate - 8 - node, Bytes().u(4, 2).s}});
  EXPECT_EQ(szip,
            "c.h5: 'grasps/transforms': its chunks pass through HDF5 filter 4, which this reader "
            "does not take (it takes deflate, shuffle and fletcher32)");
}

// Valid chunked files read as libhdf5 wrote them (no false alarm from the checks): edge chunks
// (9 x 3 values in chunks of 2 x 2: the last row and column of chunks are partly outside the
// shape but stored whole), shuffle + deflate + fletcher32 (the checksum after the deflated bytes),
// and a tree of two levels (200 chunks; a node holds at most 64).
TEST(Hdf5Structure, ValidChunkedFilesReadWhateverTheirFilters) {
  test::TempDir dir;
  const auto path = dir.path() / "v.h5";
  const auto series = [](std::size_t n) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = 0.5 * static_cast<double>(i) - 3.0;
    return v;
  };
  for (const bool filtered : {false, true}) {
    test::writeHdf5(path, {{"a", {9, 3}, series(27), false, false, "", {2, 2}, filtered, filtered},
                           {"b", {400}, series(400), false, false, "", {2}, filtered, filtered}});
    const std::string bytes = readFileBytes(path, 1 << 22);
    // The two-level tree: a node of level 1 is there.
    EXPECT_NE(bytes.find(std::string("TREE\x01\x01", 6)), std::string::npos);
    const Hdf5File h5 = Hdf5File::fromBytes(bytes, "v.h5");
    EXPECT_EQ(h5.numbers("a").values, series(27)) << filtered;
    EXPECT_EQ(h5.numbers("b").values, series(400)) << filtered;
  }
}

// libhdf5 keeps a record of every chunk a read touches, written or not: a damaged shape of 2.6
// million values in chunks of 2 (fuzz/regressions/hdf5/chunks-2.6-million) took more than 2 GB.
// At most 65,536 chunks are read: 131,072 values in chunks of 2 are (their fill value, 0, as no
// chunk was written), 200,000 are refused before libhdf5 reads them.
TEST(Hdf5Structure, ADatasetOfTooManyChunksIsRefused) {
  test::TempDir dir;
  const auto path = dir.path() / "n.h5";
  const std::string key = "grasps/qualities/flex/object_in_gripper";
  test::writeHdf5(path, {{key, {131072}, {}, true, false, "", {2}}});
  EXPECT_EQ(Hdf5File::open(path).numbers(key).values, std::vector<double>(131072, 0.0));
  test::writeHdf5(path, {{key, {200000}, {}, true, false, "", {2}}});
  EXPECT_EQ(errorOf([&] { Hdf5File::open(path).numbers(key); }),
            path.string() + ": dataset '" + key +
                "' is stored in more than 65536 chunks (chunks of 2 for a shape of 200000), more "
                "than this reader reads");
}

// A variable-length string (ACRONYM's object/file) points into a global heap collection; one
// written by libhdf5 reads, and the fuzz stage's damaged collection (an object claiming more
// bytes than the collection holds, which libhdf5 1.10.8 copied 4,040 bytes past its buffer) and
// a reference to an object the collection lacks are refused before libhdf5 reads them.
TEST(Hdf5Structure, VariableLengthStringsNeedTheirGlobalHeapObject) {
  test::TempDir dir;
  const auto path = dir.path() / "s.h5";
  test::writeHdf5(path, {{"object/file", {}, {}, false, true, "meshes/Table/x.obj"}});
  const std::string good = readFileBytes(path, 1 << 20);
  EXPECT_EQ(Hdf5File::fromBytes(good, "s.h5").text("object/file"), "meshes/Table/x.obj");
  const std::size_t gcol = good.find("GCOL");
  ASSERT_NE(gcol, std::string::npos);
  // The first object (index 1) follows the 16-byte collection header: its size is at +8.
  std::string big = good;
  big.replace(gcol + 16 + 8, 8, Bytes().u(1 << 20, 8).s);
  EXPECT_NE(errorOf([&] { Hdf5File::fromBytes(big, "s.h5").text("object/file"); })
                .find("s.h5: damaged HDF5 file: dataset 'object/file': object 1 of its string's "
                      "global heap claims 1048576 bytes, more than the heap holds"),
            std::string::npos);
  std::string other = good;
  other.replace(gcol + 16, 2, Bytes().u(7, 2).s);  // the object is now number 7
  EXPECT_NE(errorOf([&] {
              Hdf5File::fromBytes(other, "s.h5").text("object/file");
            }).find("its string's global heap has no object 1"),
            std::string::npos);
  // An object longer than the string (libhdf5 copies the object into a buffer sized by the
  // string: 24 bytes into 18 here; the object stays 24 bytes padded, so the walk is unchanged).
  std::string longer = good;
  longer.replace(gcol + 16 + 8, 8, Bytes().u(24, 8).s);
  EXPECT_NE(errorOf([&] {
              Hdf5File::fromBytes(longer, "s.h5").text("object/file");
            }).find("its string has 18 bytes, its global heap object 1 holds 24"),
            std::string::npos);
  // A length of 0 does not make libhdf5 skip the collection (only an address of 0 does): a
  // damaged collection is refused all the same.
  const std::size_t reference = good.find(Bytes().u(18, 4).u(gcol, 8).s);
  ASSERT_NE(reference, std::string::npos);
  std::string empty = big;
  empty.replace(reference, 4, Bytes().u(0, 4).s);
  EXPECT_NE(errorOf([&] {
              Hdf5File::fromBytes(empty, "s.h5").text("object/file");
            }).find("more than the heap holds"),
            std::string::npos);
  const auto known = std::filesystem::path(VISGRAB_SOURCE_DIR) /
                     "fuzz/regressions/hdf5/vlen-string-heap-overflow-1";
  EXPECT_NE(errorOf([&] { Hdf5File::open(known).text("object/file"); }).find("global heap"),
            std::string::npos);
}

// Every input the fuzz stage found (fuzz/regressions/hdf5: huge allocations, crashes and endless
// loops inside libhdf5) is an ImportError naming the file for at least one of the datasets the
// ACRONYM importers read (and nothing else escapes).
TEST(Hdf5Structure, EveryFuzzFindingIsAnImportErrorNamingTheFile) {
  const auto dir = std::filesystem::path(VISGRAB_SOURCE_DIR) / "fuzz/regressions/hdf5";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    int refused = 0;
    for (const std::string key : {"grasps/transforms", "grasps/qualities/flex/object_in_gripper",
                                  "object/scale", "object/com", "object/inertia", "object/file"}) {
      const std::string error = errorOf([&] {
        const Hdf5File h5 = Hdf5File::open(entry.path());
        if (key == "object/file") {
          h5.text(key);
        } else {
          h5.numbers(key);
        }
      });
      if (error.empty()) continue;
      EXPECT_EQ(error.rfind(entry.path().string() + ":", 0), 0U) << error;
      // One of this reader's own checks, not only libhdf5's refusal of what it then read.
      if (error.find("damaged") != std::string::npos ||
          error.find("has elements of") != std::string::npos ||
          error.find("chunks, more than this reader reads") != std::string::npos) {
        ++refused;
      }
    }
    EXPECT_GT(refused, 0) << entry.path();
  }
  EXPECT_GE(files, 5);
}

}  // namespace
}  // namespace visgrab::importers
