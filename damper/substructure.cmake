# brfd-substructure: the damper substructure process (virtual BRFD over LCM).
add_library(damper_substructure ${CMAKE_CURRENT_LIST_DIR}/substructure_node.cc)
target_link_libraries(damper_substructure PUBLIC damper messages)
add_executable(brfd-substructure ${CMAKE_CURRENT_LIST_DIR}/substructure_main.cc)
target_link_libraries(brfd-substructure PRIVATE damper_substructure CLI11::CLI11)
