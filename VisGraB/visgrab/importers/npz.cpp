#include "visgrab/importers/npz.hpp"

#include <zip.h>

#include <memory>

#include "visgrab/importers/npy.hpp"

namespace visgrab::importers {

namespace {

struct ArchiveCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
struct EntryCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

std::string zipErrorText(zip_error_t* error) {
  const char* text = zip_error_strerror(error);
  return text != nullptr ? text : "unknown zip error";
}

std::map<std::string, std::string> readMembers(zip_t* archive, const std::string& name) {
  std::map<std::string, std::string> members;
  const zip_int64_t n = zip_get_num_entries(archive, 0);
  std::size_t total = 0;
  for (zip_int64_t i = 0; i < n; ++i) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(archive, static_cast<zip_uint64_t>(i), 0, &st) != 0 ||
        (st.valid & ZIP_STAT_NAME) == 0 || (st.valid & ZIP_STAT_SIZE) == 0) {
      throw ImportError(name + ": zip member " + std::to_string(i) +
                        " cannot be read: " + zipErrorText(zip_get_error(archive)));
    }
    std::string member = st.name;
    if (!member.empty() && member.back() == '/') continue;  // a folder entry
    if (st.size > kMaxArrayBytes || total + st.size > 4 * kMaxArrayBytes) {
      throw ImportError(name + ": member " + member + " has " + std::to_string(st.size) +
                        " bytes, more than this reader accepts (" + std::to_string(kMaxArrayBytes) +
                        " per array)");
    }
    std::unique_ptr<zip_file_t, EntryCloser> entry(
        zip_fopen_index(archive, static_cast<zip_uint64_t>(i), 0));
    if (!entry) {
      throw ImportError(name + ": member " + member +
                        " cannot be opened: " + zipErrorText(zip_get_error(archive)));
    }
    // Read in chunks, so that a member that lies about its size allocates only what it holds.
    std::string bytes;
    char buffer[65536];
    while (true) {
      const zip_int64_t got = zip_fread(entry.get(), buffer, sizeof(buffer));
      if (got < 0) {
        throw ImportError(name + ": member " + member +
                          " is damaged: " + zipErrorText(zip_file_get_error(entry.get())));
      }
      if (got == 0) break;
      bytes.append(buffer, static_cast<std::size_t>(got));
      if (bytes.size() > st.size || bytes.size() > kMaxArrayBytes) {
        throw ImportError(name + ": member " + member + " holds more than its recorded " +
                          std::to_string(st.size) + " bytes");
      }
    }
    if (bytes.size() != st.size) {
      throw ImportError(name + ": member " + member + " holds " + std::to_string(bytes.size()) +
                        " bytes, its record says " + std::to_string(st.size));
    }
    total += bytes.size();
    std::string key = member;
    if (key.size() > 4 && key.compare(key.size() - 4, 4, ".npy") == 0) key.resize(key.size() - 4);
    members[key] = std::move(bytes);
  }
  return members;
}

}  // namespace

NpzFile NpzFile::open(const std::filesystem::path& file) {
  return fromBytes(readFileBytes(file, 4 * kMaxArrayBytes), file.string());
}

NpzFile NpzFile::fromBytes(std::string_view bytes, const std::string& name) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  if (source == nullptr) {
    const std::string text = zipErrorText(&error);
    zip_error_fini(&error);
    throw ImportError(name + ": cannot read it as a zip (.npz): " + text);
  }
  std::unique_ptr<zip_t, ArchiveCloser> archive(zip_open_from_source(source, ZIP_RDONLY, &error));
  if (!archive) {
    zip_source_free(source);
    const std::string text = zipErrorText(&error);
    zip_error_fini(&error);
    throw ImportError(name + ": not a zip (.npz) file: " + text);
  }
  zip_error_fini(&error);
  NpzFile out;
  out.name_ = name;
  out.members_ = readMembers(archive.get(), name);
  return out;
}

std::vector<std::string> NpzFile::names() const {
  std::vector<std::string> out;
  for (const auto& [key, bytes] : members_) out.push_back(key);
  return out;
}

NdArray NpzFile::array(const std::string& key) const {
  const auto it = members_.find(key);
  if (it == members_.end()) {
    std::string there;
    for (const auto& [k, bytes] : members_) there += (there.empty() ? "" : ", ") + k;
    throw ImportError(name_ + ": no array '" + key + "' (member " + key + ".npy); it has " +
                      (there.empty() ? std::string("no arrays") : there));
  }
  return parseNpy(it->second, name_ + ": array '" + key + "'");
}

}  // namespace visgrab::importers
