# Warnings and sanitizers, set in one place and applied per target.
function(contour_reg_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter>)
endfunction()

if(CONTOUR_REG_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "CONTOUR_REG_BUILD_FUZZERS needs clang: CC=clang CXX=clang++ cmake ...")
  endif()
  set(CONTOUR_REG_SANITIZE ON)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(CONTOUR_REG_SANITIZE)
  # Under AddressSanitizer Eigen stops trusting malloc's 16-byte alignment and frees with its
  # own scheme, while the PCL libraries (built without it) allocate with plain malloc: keep
  # the two in agreement, or every cloud PCL grows and this code frees looks corrupt.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# In the sanitizer build the tests and the command-line tool compile without optimization: the
# computation they check runs in the libraries, optimized as the build type says, and most of
# their compile time is spent optimizing CLI11's, GoogleTest's and PCL's inline code.
function(contour_reg_set_driver_options target)
  if(CONTOUR_REG_SANITIZE AND NOT CONTOUR_REG_BUILD_FUZZERS)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()
