#pragma once
// The HDF5 types of the C++ types the DEM's files store: the type in the file (little-endian,
// IEEE 754 binary64 for doubles, so values round-trip exactly), the type in memory, and the class
// a file type must have to be read as it.
//
// Include only from .cc files: hdf5.h (the OpenMPI flavour) pulls in mpi.h.
#include <hdf5.h>

#include <cstdint>

namespace geohybrid::dem::hdf5
{
template <typename T>
struct Type;
template <>
struct Type<double>
{
  static hid_t file() { return H5T_IEEE_F64LE; }
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static constexpr H5T_class_t type_class = H5T_FLOAT;
};
template <>
struct Type<std::int64_t>
{
  static hid_t file() { return H5T_STD_I64LE; }
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
};
template <>
struct Type<std::uint64_t>
{
  static hid_t file() { return H5T_STD_U64LE; }
  static hid_t memory() { return H5T_NATIVE_UINT64; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
};
template <>
struct Type<std::uint32_t>
{
  static hid_t file() { return H5T_STD_U32LE; }
  static hid_t memory() { return H5T_NATIVE_UINT32; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
};
template <>
struct Type<std::uint8_t>
{
  static hid_t file() { return H5T_STD_U8LE; }
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
};
} // namespace geohybrid::dem::hdf5
