# `cmake --install BUILD --prefix P` and `cpack -G DEB`: the program, its OpenImageIO module and
# what it finds beside itself (core/install_layout.h): the default scenes, their particle files,
# the example shaders, the docs and the example CI files, under P/share/twinrender/.
install(TARGETS twinrender RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(TARGETS twinrender_oiio LIBRARY DESTINATION "${TWINRENDER_INSTALL_MODULEDIR}")
install(DIRECTORY scenes data examples docs DESTINATION "${TWINRENDER_INSTALL_RESOURCEDIR}")
install(DIRECTORY ci/examples DESTINATION "${TWINRENDER_INSTALL_RESOURCEDIR}/ci")
foreach(_doc README.md CONTRIBUTING.md)
  if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/${_doc}")
    install(FILES "${_doc}" DESTINATION "${TWINRENDER_INSTALL_RESOURCEDIR}")
  endif()
endforeach()

# The Debian package: its dependencies are the Debian packages of the libraries the program and
# the module link (dpkg-shlibdeps), plus Mesa's EGL and llvmpipe, which the program loads
# through libglvnd without linking them (a GPU driver with EGL is used first where present).
set(CPACK_PACKAGE_NAME twinrender)
set(CPACK_PACKAGE_CONTACT "twinrender maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Particle renderer compared buffer by buffer against an Embree reference raymarcher")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libegl1 is libglvnd's libEGL.so.1, which libepoxy opens at run time (no link names it, so
# dpkg-shlibdeps cannot find it); a debootstrap'ed Debian 12 lacks it.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libegl-mesa0, libgl1-mesa-dri")
# ffmpeg: videos of sequences (optional; reports say when it is missing).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "ffmpeg")
# `cmake --install` and cpack need only the installed targets built (scripts/package builds
# them), not the tests and benchmarks.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)
include(CPack)
