// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatBackend
 * @brief   the rendering backends of the splat mappers, and the automatic choice between them
 *
 * Both splat mappers render either on the multithreaded CPU rasterizer or through OpenGL. AUTO
 * picks OpenGL on a hardware GPU and the CPU where the window's OpenGL renderer is a software
 * one (Mesa's llvmpipe, softpipe or swrast), whose vertex and fragment stages are slower than
 * the CPU rasterizer.
 */
#ifndef vtkSplatBackend_h
#define vtkSplatBackend_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"

class vtkRenderWindow;

class SPLATRENDERING_EXPORT vtkSplatBackend : public vtkObject
{
public:
  static vtkSplatBackend* New();
  vtkTypeMacro(vtkSplatBackend, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Backends
  {
    AUTO = 0,   ///< OpenGL on a hardware GPU, CPU under a software OpenGL renderer
    CPU = 1,    ///< the multithreaded CPU rasterizer
    OPENGL = 2, ///< OpenGL shaders
  };

  /**
   * "Auto", "CPU" or "OpenGL"; "Unknown" for other values.
   */
  static const char* GetBackendAsString(int backend);

  /**
   * True when the window's OpenGL renderer string names a software rasterizer. The window's
   * context must be current (as it is while rendering).
   */
  static bool IsSoftwareRenderer(vtkRenderWindow* window);

  /**
   * The backend that renders: CPU or OPENGL, never AUTO.
   */
  static int Resolve(int requested, vtkRenderWindow* window);

protected:
  vtkSplatBackend() = default;
  ~vtkSplatBackend() override = default;

private:
  vtkSplatBackend(const vtkSplatBackend&) = delete;
  void operator=(const vtkSplatBackend&) = delete;
};

#endif
