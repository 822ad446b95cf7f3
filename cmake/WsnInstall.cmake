# What `cmake --install BUILD --prefix P` (and the .deb) puts in place: the commands, the role
# executables, the python tools, scenarios, sweep specs, IDL, examples and docs. Test and bench binaries stay out.
include(${PROJECT_SOURCE_DIR}/cmake/WsnInstallDirs.cmake)

# The user-facing commands. examples/watch_tracks is not among them: it is an example to read and
# build, shipped as source with the IDL; `wsntrack watch` is the installed viewer.
install(TARGETS wsntrack wsntrack-network-calibrate RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS wsntrack-node wsntrack-network wsntrack-supernode wsntrack-aggregator
        RUNTIME DESTINATION ${WSN_INSTALL_ROLE_DIR})

# The run loader is imported, and run alone it prints what a run directory holds.
install(PROGRAMS tools/plot_run.py tools/sweep.py tools/wsntrack_run.py tools/onera_table.py DESTINATION ${WSN_INSTALL_TOOLS_DIR})
# The package the tools are entry points over, in the python path of the prefix it is installed into
# (cmake/WsnInstallDirs.cmake), with the catalogue of the wsntrack installed beside it
# (launcher/CMakeLists.txt writes it); and python-path beside the tools: where it is, relative to
# them (in the source and build trees they look in ../python instead). Decided at install time, when
# CMAKE_INSTALL_PREFIX is the prefix installed into. file(INSTALL) adds DESTDIR itself; file(WRITE)
# is given it.
install(CODE "
  if(CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
    set(wsn_python_dir \"${WSN_INSTALL_PYTHON_DIR_USR}\")
  else()
    set(wsn_python_dir \"${WSN_INSTALL_PYTHON_DIR_OTHER}\")
  endif()
  file(INSTALL \"${PROJECT_SOURCE_DIR}/python/wsntrack\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${wsn_python_dir}\"
       FILES_MATCHING PATTERN \"*.py\" PATTERN \"__pycache__\" EXCLUDE)
  file(INSTALL \"${WSN_BUILD_CATALOGUE}\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${wsn_python_dir}/wsntrack\")
  file(RELATIVE_PATH wsn_python_from_tools \"/prefix/${WSN_INSTALL_TOOLS_DIR}\" \"/prefix/\${wsn_python_dir}\")
  file(WRITE \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${WSN_INSTALL_TOOLS_DIR}/python-path\" \"\${wsn_python_from_tools}\\n\")
  message(STATUS \"Installing: the python package into \$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/\${wsn_python_dir}\")
")

install(DIRECTORY scenarios/ DESTINATION ${WSN_INSTALL_SCENARIO_DIR} FILES_MATCHING PATTERN "*.yaml")
# The sweep specs name their scenario relative to the data directory, where the scenarios are too.
install(DIRECTORY sweeps/ DESTINATION ${WSN_INSTALL_DATA_DIR}/sweeps FILES_MATCHING PATTERN "*.yaml")
install(DIRECTORY idl/ DESTINATION ${WSN_INSTALL_IDL_DIR} FILES_MATCHING PATTERN "*.idl")

# The docs keep the repository's relative layout, so that the links between them still resolve.
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs FILES_MATCHING PATTERN "*.md")
install(FILES scenarios/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}/scenarios)
# Sources and README only: the examples' CMakeLists.txt builds them inside this project, not from an install.
install(DIRECTORY examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        FILES_MATCHING PATTERN "*.md" PATTERN "*.c" PATTERN "*.h" PATTERN "*.cpp" PATTERN "*.hpp" PATTERN "*.py"
        PATTERN "__pycache__" EXCLUDE)
