# The DDS side of the aggregator role.
add_library(wsn_aggregator_role STATIC ${CMAKE_CURRENT_LIST_DIR}/role.cpp)
target_link_libraries(wsn_aggregator_role PUBLIC wsn_aggregator_core wsn_dds PRIVATE wsn_provenance)
add_executable(wsntrack-aggregator ${CMAKE_CURRENT_LIST_DIR}/main.cpp)
target_link_libraries(wsntrack-aggregator PRIVATE wsn_aggregator_role wsn_role_main wsn_scenario)
