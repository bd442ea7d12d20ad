# The `Sanitize` build type: AddressSanitizer and UndefinedBehaviorSanitizer on the project's own
# code (VTK, ParaView, Mesa and the other libraries are Debian's, built without them; the ASan
# runtime is linked into our executables and libraries). `./splat test --sanitize` configures
# build/sanitize with it and runs the tests labeled `sanitize` (Testing/Cxx/CMakeLists.txt).
# float-cast-overflow (not part of GCC's `undefined`) catches NaN, Inf and out-of-range floats
# converted to integers: pixel and index computations from bad input. -O1 keeps the tests fast
# enough and the stacks readable; every UBSan finding is fatal (-fno-sanitize-recover=all), so a
# test fails on the first one.
set(splat_sanitize_flags "-O1 -g -fsanitize=address,undefined,float-cast-overflow \
-fno-omit-frame-pointer -fno-sanitize-recover=all")
set(splat_sanitize_link_flags "-fsanitize=address,undefined,float-cast-overflow")
# Plain variables, not cache entries: CMake creates empty cache entries for a custom build type
# at project(), which a cache default would not replace.
foreach (lang IN ITEMS C CXX)
  set(CMAKE_${lang}_FLAGS_SANITIZE "${splat_sanitize_flags}")
endforeach ()
foreach (kind IN ITEMS EXE SHARED MODULE)
  set(CMAKE_${kind}_LINKER_FLAGS_SANITIZE "${splat_sanitize_link_flags}")
endforeach ()

if (CMAKE_BUILD_TYPE STREQUAL "Sanitize")
  set(SPLAT_SANITIZE ON)
else ()
  set(SPLAT_SANITIZE OFF)
endif ()
