# Python wrapping of the Splat modules with VTK's own wrapping (system VTK build only, included
# from the top CMakeLists.txt), as the package `splat` next to VTK's `vtkmodules`:
#   <build>/lib/python3/dist-packages/splat/__init__.py        imports every class below
#   <build>/lib/python3/dist-packages/splat/SplatRendering*.so  one extension module per VTK module
# Put <build>/lib/python3/dist-packages on PYTHONPATH and run the Python that VTK was wrapped for
# (Debian's /usr/bin/python3; `./splat python` does both).

set(splat_python_destination "${VTK_PYTHONPATH}")
set(SPLAT_PYTHONPATH "${CMAKE_BINARY_DIR}/${splat_python_destination}" CACHE INTERNAL
  "The build tree's site-packages folder holding the splat package")

vtk_module_wrap_python(
  MODULES             ${splat_modules}
  TARGET              Splat::SplatPython
  WRAPPED_MODULES     splat_wrapped_modules
  INSTALL_EXPORT      SplatPython
  PYTHON_PACKAGE      "splat"
  MODULE_DESTINATION  "${splat_python_destination}"
  CMAKE_DESTINATION   "${CMAKE_INSTALL_LIBDIR}/cmake/Splat"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  SOABI               "${Python3_SOABI}"
  BUILD_STATIC        OFF)

# splat/__init__.py: every wrapped module's classes at the package level (`from splat import
# vtkSurfaceSplatMapper`), as vtkmodules.all does for VTK's.
set(splat_python_init "")
foreach (module IN LISTS splat_wrapped_modules)
  vtk_module_get_property("${module}" PROPERTY "INTERFACE_vtk_module_library_name"
    VARIABLE library)
  string(APPEND splat_python_init "from .${library} import *\n")
endforeach ()
file(GENERATE
  OUTPUT  "${SPLAT_PYTHONPATH}/splat/__init__.py"
  CONTENT "\"\"\"Splat: EWA surface and volume splatting for VTK.\"\"\"\n${splat_python_init}")
install(
  FILES       "${SPLAT_PYTHONPATH}/splat/__init__.py"
  DESTINATION "${splat_python_destination}/splat"
  COMPONENT   python)
