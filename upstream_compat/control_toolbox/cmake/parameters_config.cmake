# control_toolbox's own build step, before name_standin.cmake: Pid's dynamic_reconfigure server needs
# control_toolbox/ParametersConfig.h, generated from cfg/Parameters.cfg into the devel space's include folder.
find_package(catkin REQUIRED COMPONENTS dynamic_reconfigure)
generate_dynamic_reconfigure_options(cfg/Parameters.cfg)
# That put the devel include first among the folders the config hands on; the config checks a package's includes of
# control_toolbox against the first folder (standin-extras.cmake.in), which must be this package's, with pid.h.
list(INSERT ${PROJECT_NAME}_INCLUDE_DIRS 0 ${CMAKE_CURRENT_SOURCE_DIR}/include)
