#include "test_files.hpp"

#include <hdf5.h>
#include <zip.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace visgrab::test {

std::string npyBytes(const std::string& descr, const std::vector<std::size_t>& shape,
                     const std::string& data, bool fortranOrder, int major) {
  std::string shapeText = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    shapeText += (i > 0 ? ", " : "") + std::to_string(shape[i]);
  }
  if (shape.size() == 1) shapeText += ",";
  shapeText += ")";
  std::string header = "{'descr': '" + descr +
                       "', 'fortran_order': " + (fortranOrder ? "True" : "False") +
                       ", 'shape': " + shapeText + ", }";
  const std::size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out("\x93NUMPY", 6);
  out += static_cast<char>(major);
  out += '\0';
  const std::size_t n = header.size();
  out += static_cast<char>(n & 0xFF);
  out += static_cast<char>((n >> 8) & 0xFF);
  if (major != 1) {
    out += static_cast<char>((n >> 16) & 0xFF);
    out += static_cast<char>((n >> 24) & 0xFF);
  }
  return out + header + data;
}

std::string f8(const std::vector<double>& values) {
  std::string out(values.size() * 8, '\0');
  std::memcpy(out.data(), values.data(), out.size());  // x86-64: little-endian
  return out;
}

std::string f4(const std::vector<float>& values) {
  std::string out(values.size() * 4, '\0');
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

void writeZip(const std::filesystem::path& file,
              const std::vector<std::pair<std::string, std::string>>& members, bool compress) {
  int error = 0;
  zip_t* z = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (z == nullptr) throw std::runtime_error("cannot create " + file.string());
  for (const auto& [name, bytes] : members) {
    zip_source_t* source = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    const zip_int64_t index = zip_file_add(z, name.c_str(), source, ZIP_FL_OVERWRITE);
    if (index < 0) throw std::runtime_error("cannot add " + name);
    zip_set_file_compression(z, static_cast<zip_uint64_t>(index),
                             compress ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
  }
  if (zip_close(z) != 0) throw std::runtime_error("cannot write " + file.string());
}

void writeHdf5(const std::filesystem::path& file, const std::vector<H5Dataset>& datasets) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot create " + file.string());
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  for (const H5Dataset& d : datasets) {
    if (d.isText) {
      const hid_t type = H5Tcopy(H5T_C_S1);
      H5Tset_size(type, H5T_VARIABLE);
      const hid_t space = H5Screate(H5S_SCALAR);
      const hid_t set = H5Dcreate2(f, d.path.c_str(), type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
      const char* text = d.text.c_str();
      H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
      H5Dclose(set);
      H5Sclose(space);
      H5Tclose(type);
      continue;
    }
    const hid_t space = d.shape.empty() ? H5Screate(H5S_SCALAR)
                                        : H5Screate_simple(static_cast<int>(d.shape.size()),
                                                           d.shape.data(), nullptr);
    const hid_t fileType = d.integer ? H5T_STD_I64LE : H5T_IEEE_F64LE;
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (!d.chunks.empty()) {
      H5Pset_chunk(dcpl, static_cast<int>(d.chunks.size()), d.chunks.data());
      if (d.shuffleAndChecksum) H5Pset_shuffle(dcpl);
      if (d.deflate) H5Pset_deflate(dcpl, 4);
      if (d.shuffleAndChecksum) H5Pset_fletcher32(dcpl);
    }
    const hid_t set = H5Dcreate2(f, d.path.c_str(), fileType, space, lcpl, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    if (set < 0) throw std::runtime_error("cannot create dataset " + d.path);
    if (!d.values.empty()) {
      H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data());
    }
    H5Dclose(set);
    H5Sclose(space);
  }
  H5Pclose(lcpl);
  H5Fclose(f);
}

::testing::AssertionResult hasSubstr(const char* textExpr, const char* partExpr,
                                     const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << textExpr << " is\n  \"" << text << "\"\nwhich does not contain " << partExpr
         << ":\n  \"" << part << "\"";
}

}  // namespace visgrab::test
