// SPDX-License-Identifier: BSD-3-Clause
// The capture formats of vtkGaussianSplatReader (private to SplatFilters): the output arrays
// filled from the INRIA layout's quantities, bounds-checked byte access, decompression, and one
// decoder per compressed format (SplatCaptureSPZ.cxx, SplatCaptureSOG.cxx, ...).
//
// Every decoder reads its header before allocating, throws splatply::ReadError (an error code
// and a message without the file name) for truncated or corrupt input, and calls `progress`
// with the fraction done. Spherical harmonics are stored in the INRIA convention whatever the
// file's: coefficient k >= 1 of channel c is the INRIA f_rest value of that coefficient.
#ifndef SplatCaptureFormats_h
#define SplatCaptureFormats_h

#include "SplatPLYFormat.h" // For splatply::ReadError
#include "vtkFloatArray.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

class vtkPolyData;

namespace splatcapture
{
using splatply::ReadError;
using Progress = std::function<void(double)>;

// The degree-0 real spherical harmonic, 1 / (2 sqrt(pi)).
constexpr double C0 = 0.28209479177387814;

// Spherical-harmonic coefficients per channel beyond the DC term for degree 0 .. 3.
constexpr int RestCoefficients(int degree)
{
  return (degree + 1) * (degree + 1) - 1;
}

// The vertex properties every INRIA capture .ply has.
inline constexpr const char* PLYProperties[] = { "x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2",
  "opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3" };

// The capture file formats vtkGaussianSplatReader reads.
enum class Format
{
  Unknown,
  PLY,           // INRIA .ply
  CompressedPLY, // PlayCanvas chunked .ply
  Splat,         // antimatter15 .splat
  SPZ,           // Niantic .spz, versions 2 to 4
  SOG,           // PlayCanvas .sog archive or its meta.json folder
  GLTF,          // .glb or .gltf with KHR_gaussian_splatting
  KSplat         // GaussianSplats3D .ksplat
};

// The format of `fileName`, from its first bytes (and, where the bytes cannot tell, its name);
// Unknown when it cannot be opened or is not a capture.
Format Identify(const std::string& fileName);
const char* FormatName(Format format);

// Spherical-harmonic coefficients turned with the Gaussians they color. Where positions and
// orientations are mapped by an orthogonal Q (a rotation or a reflection), the color seen along
// d must be the one seen before along Q^T d: band l turns by the (2l+1)^2 block M_l with
// Y_l(d) M_l = Y_l(Q^T d). Each block is fitted once per Q by least squares over directions
// spread on the sphere (exact, a band being closed under rotations) from the mapper's own basis
// (SplatSphericalHarmonics.h), so that its order and signs carry over unchanged.
class HarmonicsTurn
{
public:
  // `q` row-major, x' = q x; `degree` 0 to 3.
  HarmonicsTurn(const double q[3][3], int degree);

  // Coefficients 1 .. RestCoefficients(degree) of one Gaussian, RGB interleaved, in place.
  void Apply(float* rest) const;

private:
  int Degree;
  std::vector<float> Blocks; // band 1's 3x3, band 2's 5x5, band 3's 7x7, row-major
};

// The output arrays of vtkGaussianSplatReader for `count` Gaussians, set one Gaussian at a time
// from the quantities of the INRIA layout. The setters are thread-safe for distinct indices.
class Kernels
{
public:
  Kernels(vtkIdType count, int degree);

  vtkIdType Count() const { return this->NumberOfGaussians; }
  int Degree() const { return this->SHDegree; }

  void SetPosition(vtkIdType i, float x, float y, float z);
  // Linear standard deviations, or their logarithms as INRIA stores them.
  void SetScale(vtkIdType i, float sx, float sy, float sz);
  void SetLogScale(vtkIdType i, float lx, float ly, float lz);
  // A quaternion w first, normalized here; zero and non-finite ones are kept for the mapper to
  // skip and count.
  void SetRotation(vtkIdType i, float w, float x, float y, float z);
  // The peak opacity in [0, 1], or its logit as INRIA stores it.
  void SetOpacity(vtkIdType i, float opacity);
  void SetOpacityLogit(vtkIdType i, float logit);
  // The DC coefficients f_dc of the three channels; sets the base color 0.5 + C0 f_dc.
  void SetDC(vtkIdType i, float r, float g, float b);
  // A base color in [0, 1] (formats that store no coefficients): f_dc = (color - 0.5) / C0.
  void SetColor(vtkIdType i, float r, float g, float b);
  // Coefficient k (1 .. RestCoefficients(Degree())) of channel c (0 .. 2).
  void SetRest(vtkIdType i, int k, int c, float value)
  {
    this->Harmonics[(static_cast<std::size_t>(i) * (this->PerChannel + 1) + k) * 3 + c] = value;
  }

  // Turns the coefficients set for Gaussian i (after its SetRest calls).
  void TurnRest(vtkIdType i, const HarmonicsTurn& turn)
  {
    turn.Apply(this->Harmonics + (static_cast<std::size_t>(i) * (this->PerChannel + 1) + 1) * 3);
  }

  // Flags kept as field data (for instance .spz's antialiasing flag).
  void SetFlag(const char* name, int value);

  // Moves the arrays into `output`: the points and the point arrays Scale, Rotation, Opacity,
  // Color and, for degree > 0, SphericalHarmonics.
  void MoveTo(vtkPolyData* output);

private:
  vtkIdType NumberOfGaussians;
  int SHDegree;
  int PerChannel;
  vtkSmartPointer<vtkFloatArray> Points, Scale, Rotation, Opacity, Color, SH;
  float* Harmonics = nullptr;
  std::vector<std::pair<std::string, int>> Flags;
};

// Bounds-checked reading of little-endian values from a byte buffer; running past its end
// throws a ReadError saying what was being read.
class Bytes
{
public:
  Bytes(const std::uint8_t* data, std::size_t size, std::string what)
    : Data(data)
    , Size(size)
    , What(std::move(what))
  {
  }

  std::size_t Offset() const { return this->Position; }
  std::size_t Remaining() const { return this->Size - this->Position; }

  // The next n bytes, which must be there.
  const std::uint8_t* Take(std::size_t n, const char* item);

  template <typename T>
  T Read(const char* item)
  {
    T value;
    std::memcpy(&value, this->Take(sizeof(T), item), sizeof(T));
    return splatply::HostIsLittleEndian() ? value : SwapBytes(value);
  }

  void Skip(std::size_t n, const char* item) { this->Take(n, item); }

private:
  template <typename T>
  static T SwapBytes(T value)
  {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    std::reverse(bytes, bytes + sizeof(T));
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Position = 0;
  std::string What;
};

// The whole file, or an error; `limit` bounds what is accepted.
std::vector<std::uint8_t> ReadFile(const std::string& fileName, std::size_t limit);
// gzip (or zlib) data inflated. With `prefix`, its first `limit` bytes (fewer where the
// stream ends before); without, more than `limit` bytes is an error (a bomb or a corrupt size).
std::vector<std::uint8_t> Gunzip(
  const std::uint8_t* data, std::size_t size, std::size_t limit, bool prefix);

// The PLY file read by vtkSplatPLYReader (with `allElements`, every element's properties as
// field data); its error, without the file name, thrown as a ReadError.
vtkSmartPointer<vtkPolyData> ReadPLYFile(
  const std::string& fileName, bool allElements, const Progress& progress);

// A half-precision float's value.
float HalfToFloat(std::uint16_t half);

// The decoders, each filling the output of vtkGaussianSplatReader.
// fromRUB: the .spz is in Niantic's right-up-back frame (vtkGaussianSplatReader::SPZFromRUB).
void ReadSPZ(
  const std::string& fileName, bool fromRUB, vtkPolyData* output, const Progress& progress);
void ReadCompressedPLY(const std::string& fileName, vtkPolyData* output, const Progress& progress);
void ReadSOG(const std::string& fileName, vtkPolyData* output, const Progress& progress);
void ReadGLTF(const std::string& fileName, vtkPolyData* output, const Progress& progress);
void ReadKSplat(const std::string& fileName, vtkPolyData* output, const Progress& progress);
}

#endif
