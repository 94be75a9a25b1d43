# brfd-substructure: the damper substructure process (virtual BRFD over LCM).
add_library(damper_substructure ${CMAKE_CURRENT_LIST_DIR}/substructure_node.cc)
target_link_libraries(damper_substructure PUBLIC damper messages)
add_executable(brfd-substructure ${CMAKE_CURRENT_LIST_DIR}/substructure_main.cc)
target_link_libraries(brfd-substructure PRIVATE damper_substructure CLI11::CLI11)

# Physical mode of brfd-substructure (docs/physical.md): actuator interface, ATS compensator,
# safety layer, HMAC-authenticated commands.
add_library(damper_physical
  ${CMAKE_CURRENT_LIST_DIR}/physical/command_auth.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/ats_compensator.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/tracking.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/safety.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/actuator_interface.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/sample_recorder.cc
  ${CMAKE_CURRENT_LIST_DIR}/physical/physical_node.cc)
target_link_libraries(damper_physical PUBLIC damper messages common Eigen3::Eigen PkgConfig::SODIUM
  PRIVATE nlohmann_json::nlohmann_json)
target_link_libraries(brfd-substructure PRIVATE damper_physical)

# brfd-rig: emulator of the BRFD lab controller.
add_library(damper_rig
  ${CMAKE_CURRENT_LIST_DIR}/rig/rig_config.cc
  ${CMAKE_CURRENT_LIST_DIR}/rig/rig_simulator.cc
  ${CMAKE_CURRENT_LIST_DIR}/rig/rig_node.cc)
target_link_libraries(damper_rig PUBLIC damper_physical damper messages common PRIVATE nlohmann_json::nlohmann_json)
add_executable(brfd-rig ${CMAKE_CURRENT_LIST_DIR}/rig/rig_main.cc)
target_link_libraries(brfd-rig PRIVATE damper_rig CLI11::CLI11)
