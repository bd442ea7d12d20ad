// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatPLYReader
 * @brief   reads PLY files of every encoding into a vtkPolyData, never crashing on bad files
 *
 * vtkSplatPLYReader reads Stanford PLY files (ascii, binary_little_endian, binary_big_endian)
 * with any elements, comments and obj_info lines, and scalar and list properties of every PLY
 * type (char, uchar, short, ushort, int, uint, float, double and their int8 ... float64 names).
 *
 * Output, from the element "vertex" (which must have x, y and z):
 * - x, y, z: the points, float, or double when any of them is stored as double;
 * - nx, ny, nz: the point normals, float, named "Normals";
 * - red, green, blue and optional alpha: unsigned char point scalars named "RGB" or "RGBA"
 *   (integer values clamped to [0, 255]; floating point values taken as [0, 1] and scaled);
 * - u, v (or s, t, or texture_u, texture_v): float texture coordinates named "TCoords";
 * - every other scalar property: a point-data array of the property's type and name (the
 *   opacity, scales and rotations of 3D Gaussian Splatting files, for instance).
 * From the element "face": the list vertex_indices (or vertex_index) gives the polygons, its
 * scalar properties cell-data arrays as above (red, green, blue as "RGB" cell scalars).
 * Other elements, and list properties other than the face indices, are read and dropped.
 *
 * Robustness: every count and size in the header is checked against what the rest of the file
 * can hold before anything is allocated, list lengths and vertex indices are bounds-checked,
 * ascii values are validated against their type, and the file may end early at any byte. On
 * any problem the reader reports a vtkErrorMacro naming the file, the header line, data line
 * (ascii) or byte offset (binary) and what was wrong, sets the ErrorCode
 * (vtkErrorCode::FileFormatError, PrematureEndOfFileError or CannotOpenFileError) and leaves
 * the output empty.
 *
 * Binary data is read in large blocks and decoded one property at a time over each block, so
 * that big files (3D Gaussian Splatting captures of millions of vertices with 62 properties)
 * read at disk speed. Progress events are sent as the file is read.
 *
 * Hand-written rather than built on a PLY library because Debian has no maintained PLY
 * library package, and VTK's vtkPLYReader crashes on truncated or corrupt files.
 *
 * @sa vtkGaussianSplatReader vtkSurfelGenerator
 */
#ifndef vtkSplatPLYReader_h
#define vtkSplatPLYReader_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkStringArray;

class SPLATFILTERS_EXPORT vtkSplatPLYReader : public vtkPolyDataAlgorithm
{
public:
  static vtkSplatPLYReader* New();
  vtkTypeMacro(vtkSplatPLYReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The PLY file to read.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Off (the default): the output described above. On: the scalar properties of every element
   * (vertex, face and any other) become field-data arrays of their own type named
   * element.property ("chunk.min_x"), with no points or cells and no property required: the
   * raw content of PLY files whose elements are not a mesh, such as the chunks of a compressed
   * 3D Gaussian Splatting capture. List properties are read and dropped.
   */
  vtkSetMacro(ReadAllElements, bool);
  vtkGetMacro(ReadAllElements, bool);
  vtkBooleanMacro(ReadAllElements, bool);
  ///@}

  /**
   * Whether the file starts with a valid PLY header (only the header is read) and is not a 3D
   * Gaussian Splatting capture. ParaView's reader factory asks every reader's CanReadFile and
   * asks the user to choose when several accept: captures are left to vtkGaussianSplatReader
   * alone. This reader still reads them when asked to.
   */
  static bool CanReadFile(const char* fileName);

  /**
   * Reads only the header of `fileName` and fills `names` with the names of the vertex
   * element's properties, in file order. False (and `names` empty) when the file cannot be
   * opened, its header is invalid or it has no vertex element.
   */
  static bool GetVertexPropertyNames(const char* fileName, vtkStringArray* names);

protected:
  vtkSplatPLYReader();
  ~vtkSplatPLYReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool ReadAllElements = false;

private:
  vtkSplatPLYReader(const vtkSplatPLYReader&) = delete;
  void operator=(const vtkSplatPLYReader&) = delete;
};

#endif
