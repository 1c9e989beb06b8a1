# upstream's config hands on TinyXML (its transmission_info.h includes it; RobotHWSims parse transmissions with it):
# name_standin.cmake puts RACEBOT_STANDIN_LIBRARIES in the config's LIBRARIES.
find_library(RACEBOT_TINYXML_LIBRARY tinyxml)
if(NOT RACEBOT_TINYXML_LIBRARY)
  message(FATAL_ERROR "transmission_interface: no libtinyxml; run 'make setup' (Debian's libtinyxml-dev)")
endif()
set(RACEBOT_STANDIN_LIBRARIES ${RACEBOT_TINYXML_LIBRARY})
