// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGaussianSplatReader
 * @brief   reads 3D Gaussian Splatting captures (.ply, compressed .ply, .splat, .spz, .sog,
 *          .ksplat, glTF) as kernels for vtkVolumeSplatMapper
 *
 * vtkGaussianSplatReader reads the file formats 3D Gaussian Splatting (Kerbl et al. 2023)
 * captures ship in into a vtkPolyData of points (the Gaussians' centers, no cells) with the
 * point arrays vtkVolumeSplatMapper draws without further set-up:
 * - "Scale", 3 floats: the standard deviations along the Gaussian's axes;
 * - "Rotation", 4 floats: the unit quaternion (w, x, y, z) turning the axes into place;
 * - "Opacity", 1 float: the peak opacity of the 3DGS model, alpha(x) = opacity exp(-beta(x));
 * - "Color", 3 floats in [0, 1]: the view-independent base color, 0.5 + C0 f_dc clamped,
 *   C0 = 0.28209479177387814 the degree-0 spherical harmonic;
 * - "SphericalHarmonics" (files with higher degrees only), 3 (d + 1)^2 floats for degree d
 *   from 1 to 3: every coefficient including the DC term, coefficient-major with the channels
 *   interleaved, [k0.r, k0.g, k0.b, k1.r, k1.g, k1.b, ...], in the INRIA implementation's
 *   convention whatever the file's, so that a capture draws the same in every format.
 *
 * The format is told by the file's first bytes (by its name where they cannot tell):
 * - .ply in the layout of the INRIA implementation, read with vtkSplatPLYReader: vertex
 *   properties x, y, z, f_dc_0..2, optional f_rest_0..(3m - 1) (m = (d + 1)^2 - 1 per channel,
 *   stored channel-major: red's m coefficients, then green's, then blue's), opacity (a logit:
 *   the output is its logistic), scale_0..2 (logarithms: the output is their exponential) and
 *   rot_0..3 (a quaternion w first, normalized on output). Other properties (normals) are
 *   dropped. A number of f_rest properties other than 0, 9, 24 or 45 is an error.
 * - PlayCanvas's compressed .ply: chunks of 256 Gaussians with quantized positions, scales,
 *   colors and rotations, optional byte spherical harmonics.
 * - .splat (the antimatter15 web viewer's layout): 32-byte little-endian records of position
 *   (3 float32), scale (3 float32, linear), color and opacity (4 uint8, color/255 and
 *   opacity/255) and rotation (4 uint8, (q + 1) 128 clamped, w first).
 * - Niantic's .spz, versions 2 and 3 (gzip) and 4 (zstd streams), taken in the frame they are
 *   stored in (the .ply's, as splat-transform writes them) or, with SPZFromRUB, in the
 *   right-up-back frame the format's README names; the antialiasing flag becomes the field-data array
 *   "Antialiased".
 * - PlayCanvas's SOG: the bundled .sog archive, or the meta.json of its folder form (versions
 *   1 and 2), WebP images decoded with libwebp.
 * - GaussianSplats3D's .ksplat, compression levels 0 to 2.
 * - glTF 2.0 (.glb, .gltf) with KHR_gaussian_splatting: every Gaussian primitive of the scene,
 *   node transforms applied (the spherical harmonics turn with the rotation or reflection in
 *   them), turned from glTF's +y up into the .ply's +y down by a half turn about z.
 *
 * Invalid values (NaN, zero quaternions) are passed through: vtkVolumeSplatMapper skips and
 * counts them. Truncated or corrupt files give a vtkErrorMacro naming the file and what was
 * wrong, an ErrorCode and an empty output. Progress events are sent while reading.
 *
 * @sa vtkSplatPLYReader vtkVolumeSplatMapper
 */
#ifndef vtkGaussianSplatReader_h
#define vtkGaussianSplatReader_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class vtkPolyData;

class SPLATFILTERS_EXPORT vtkGaussianSplatReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianSplatReader* New();
  vtkTypeMacro(vtkGaussianSplatReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The capture file to read.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * The frame of .spz files. The format's README names a right-up-back frame (+y up, +z
   * toward the viewer), which Niantic's spz library writes when told its source is a .ply
   * (PackOptions::from = RDF); by default it, ply_to_spz, splat-transform, Spark and the
   * PlayCanvas viewers store the .ply's right-down-forward frame unchanged, and nothing in the
   * file tells the two apart. Off (the default): the values as stored, which reads those files
   * as their .ply. On: the file is taken as right-up-back and turned into the .ply's frame (a
   * half turn about x of the positions, the orientations and the spherical harmonics).
   */
  vtkSetMacro(SPZFromRUB, bool);
  vtkGetMacro(SPZFromRUB, bool);
  vtkBooleanMacro(SPZFromRUB, bool);
  ///@}

  /**
   * Whether `fileName` is a 3D Gaussian Splatting capture in one of the formats above: a PLY
   * file whose vertex element has the properties x, y, z, f_dc_0..2, opacity, scale_0..2 and
   * rot_0..3 or the compressed layout's packed properties (only the header is read), a file
   * named .splat whose size is a non-zero multiple of 32 bytes, or a file that starts as the
   * other formats do (a .json is taken as a SOG's meta.json).
   */
  static bool IsGaussianSplatFile(const char* fileName);

  /**
   * IsGaussianSplatFile under the name and type of VTK readers' CanReadFile: ParaView's reader
   * factory calls it, so that PLY files that are not captures are left to other readers.
   */
  static int CanReadFile(const char* fileName);

  /**
   * The degree (0 to 3) of the spherical harmonics in the last output; 0 without
   * "SphericalHarmonics", -1 before the first successful read.
   */
  vtkGetMacro(SphericalHarmonicsDegree, int);

protected:
  vtkGaussianSplatReader();
  ~vtkGaussianSplatReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool ReadPLY(vtkPolyData* output);
  bool ReadSplat(vtkPolyData* output);
  void Fail(int errorCode, const std::string& what);

  char* FileName = nullptr;
  bool SPZFromRUB = false;
  int SphericalHarmonicsDegree = -1;

private:
  vtkGaussianSplatReader(const vtkGaussianSplatReader&) = delete;
  void operator=(const vtkGaussianSplatReader&) = delete;
};

#endif
