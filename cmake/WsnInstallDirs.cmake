# Where an installed wsntrack puts each part (GNUInstallDirs underneath), and the same places relative
# to CMAKE_INSTALL_BINDIR, which launcher/install_layout.cpp is compiled with to find them at run time.
# No include_guard: launcher/ and the top level each include this, and directory scopes do not share variables.
include(GNUInstallDirs)

# The role executables go to libexec/wsntrack, not bin/: only `wsntrack run` can start them (they need
# its run directory, run id and domain), so on PATH they would be clutter under generic names.
set(WSN_INSTALL_ROLE_DIR "${CMAKE_INSTALL_LIBEXECDIR}/wsntrack")
# Architecture-independent data: the shipped scenarios, the IDL for programs of one's own, and the
# python tools. The tools are not on PATH because plot_run.py is run by wsntrack itself and the
# loader module is imported, not run; sweep.py keeps them together (the README gives the full path).
set(WSN_INSTALL_DATA_DIR "${CMAKE_INSTALL_DATADIR}/wsntrack")
set(WSN_INSTALL_SCENARIO_DIR "${WSN_INSTALL_DATA_DIR}/scenarios")
set(WSN_INSTALL_IDL_DIR "${WSN_INSTALL_DATA_DIR}/idl")
set(WSN_INSTALL_TOOLS_DIR "${WSN_INSTALL_DATA_DIR}/tools")
# The python package (`import wsntrack`) goes where Debian's /usr/bin/python3, which runs the tools,
# imports from, chosen by the prefix it is installed into (cmake/WsnInstall.cmake decides when it
# installs, so that cpack's /usr and `cmake --install --prefix P` each get theirs):
# lib/python3/dist-packages under /usr (the .deb: Debian's place for a package of any python3),
# lib/python3.X/dist-packages under any other prefix (on that python's path for /usr/local;
# PYTHONPATH for another). The tools find it through python-path, written beside them.
if(NOT DEFINED WSN_PYTHON3_MINOR)
  execute_process(COMMAND /usr/bin/python3 -c "import sys; print(sys.version_info[1])"
                  OUTPUT_VARIABLE wsn_python3_minor OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  set(WSN_PYTHON3_MINOR "${wsn_python3_minor}" CACHE INTERNAL "minor version of /usr/bin/python3")
endif()
set(WSN_INSTALL_PYTHON_DIR_USR "lib/python3/dist-packages")
if(WSN_PYTHON3_MINOR STREQUAL "")
  set(WSN_INSTALL_PYTHON_DIR_OTHER "${WSN_INSTALL_PYTHON_DIR_USR}")
else()
  set(WSN_INSTALL_PYTHON_DIR_OTHER "lib/python3.${WSN_PYTHON3_MINOR}/dist-packages")
endif()

# Relative to bindir, so that the installed tree works under any prefix (`cmake --install --prefix P`,
# the .deb's /usr). With relative GNUInstallDirs the configured prefix cancels out. An absolute
# directory (e.g. -DCMAKE_INSTALL_LIBEXECDIR=/opt/x, or an absolute bindir) cannot move with the
# prefix, so it is passed as the absolute path it is.
function(wsn_path_from_bin out_var dir)
  if(IS_ABSOLUTE "${dir}" OR IS_ABSOLUTE "${CMAKE_INSTALL_BINDIR}")
    if(IS_ABSOLUTE "${dir}")
      set(${out_var} "${dir}" PARENT_SCOPE)
    else()
      set(${out_var} "${CMAKE_INSTALL_PREFIX}/${dir}" PARENT_SCOPE)
    endif()
    return()
  endif()
  file(RELATIVE_PATH relative "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${dir}")
  if(relative STREQUAL "")
    set(relative ".")
  endif()
  set(${out_var} "${relative}" PARENT_SCOPE)
endfunction()
wsn_path_from_bin(WSN_INSTALL_ROLE_DIR_FROM_BIN "${WSN_INSTALL_ROLE_DIR}")
wsn_path_from_bin(WSN_INSTALL_TOOLS_DIR_FROM_BIN "${WSN_INSTALL_TOOLS_DIR}")
wsn_path_from_bin(WSN_INSTALL_SCENARIO_DIR_FROM_BIN "${WSN_INSTALL_SCENARIO_DIR}")
