# test_layers: the dependencies point one way (docs/design.md §1). core/ includes no Qt, nothing of
# devices/ or app/, and no GUI library; devices/ includes nothing of app/, QtWidgets or QCustomPlot.
# Run as: cmake -DSOURCE_DIR=<repository> -P CheckLayers.cmake
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "give -DSOURCE_DIR=<the repository>")
endif()

set(problems "")
function(check_folder folder)
  set(forbidden ${ARGN})
  file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${folder}/*.h"
       "${SOURCE_DIR}/${folder}/*.cpp")
  foreach(source ${sources})
    file(STRINGS "${SOURCE_DIR}/${source}" includes REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${includes})
      foreach(pattern ${forbidden})
        if(line MATCHES "${pattern}")
          string(STRIP "${line}" line)
          list(APPEND problems "${source}: ${line} (${folder}/ must not include what matches ${pattern})")
        endif()
      endforeach()
    endforeach()
  endforeach()
  set(problems "${problems}" PARENT_SCOPE)
endfunction()

# Qt headers are <Q...>, <QtCore/...> and the like; QCustomPlot is <qcustomplot.h>.
check_folder(core "<Q[A-Za-z]" "<qcustomplot" "\"app/" "\"devices/")
check_folder(devices "\"app/" "<QtWidgets" "<QWidget" "<QApplication" "<qcustomplot")

list(LENGTH problems count)
if(count GREATER 0)
  foreach(p ${problems})
    message("${p}")
  endforeach()
  message(FATAL_ERROR "${count} include(s) break the layering")
endif()
file(GLOB_RECURSE core_files "${SOURCE_DIR}/core/*.cpp" "${SOURCE_DIR}/core/*.h")
file(GLOB_RECURSE device_files "${SOURCE_DIR}/devices/*.cpp" "${SOURCE_DIR}/devices/*.h")
list(LENGTH core_files n_core)
list(LENGTH device_files n_devices)
message("layers hold: ${n_core} core files and ${n_devices} device files checked")
