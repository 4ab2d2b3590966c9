# A denoiser that fails after the render keeps the render: with the library found but its device
# plugin missing (a copy of the library without libOpenImageDenoise_device_*), `glint render
# --denoise` writes the noisy image, says that denoising failed and exits 1. And a corrupt
# library is reported with the loader's reason, not as "not found".
# GLINT: the executable; OIDN_DIR: the folder with the real libraries; OUT: a scratch folder;
# PROJECT: a project to render.
include(${CMAKE_CURRENT_LIST_DIR}/expect_exit.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/no-plugins ${OUT}/corrupt)
foreach(lib libOpenImageDenoise.so.2.5.1 libOpenImageDenoise_core.so.2.5.1 libtbb.so.12)
  file(COPY ${OIDN_DIR}/${lib} DESTINATION ${OUT}/no-plugins)
endforeach()
set(ENV{GLINT_OIDN_DIR} ${OUT}/no-plugins)
foreach(ext png exr)
  expect_exit(1 "wrote .*noisy.${ext}.*glint render: denoising failed \\([^)]*\\): .*noisy.${ext} holds the noisy image"
              ${GLINT} render ${PROJECT} -o ${OUT}/noisy.${ext} --width 24 --spp 2 --denoise)
  if(NOT EXISTS ${OUT}/noisy.${ext})
    message(FATAL_ERROR "the noisy ${ext} was not kept")
  endif()
endforeach()

# The executable beside a library that is not one: the reason names the file and the loader's
# complaint (an ELF header it cannot read).
file(COPY ${GLINT} DESTINATION ${OUT}/corrupt)
file(WRITE ${OUT}/corrupt/libOpenImageDenoise.so.2.5.1 "not a shared library\n")
unset(ENV{GLINT_OIDN_DIR})
get_filename_component(exe ${GLINT} NAME)
expect_exit(0 "denoising is unavailable \\([^\n]*corrupt/libOpenImageDenoise.so.2.5.1 cannot be loaded \\([^\n]*(ELF|too short)"
            ${OUT}/corrupt/${exe} render ${PROJECT} -o ${OUT}/corrupt.png --width 24 --spp 2 --denoise)
file(REMOVE_RECURSE ${OUT})
