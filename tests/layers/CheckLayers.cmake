# test_layers: the dependencies point one way (docs/design.md §1). core/ includes no Qt, nothing of
# devices/ or app/, and no GUI library; devices/ includes nothing of app/, QtWidgets or QCustomPlot.
# Inside core/, each folder includes only itself and the folders before it in kCoreOrder, so no
# chain of includes between core's folders runs in a circle.
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

# core's folders from the bottom up: each may include only those before it.
set(kCoreOrder common stats geometry tap fingertip io rig classify scene validation control recognition
    records experiment run analysis)
file(GLOB core_folders RELATIVE "${SOURCE_DIR}/core" "${SOURCE_DIR}/core/*")
foreach(folder ${core_folders})
  if(IS_DIRECTORY "${SOURCE_DIR}/core/${folder}")
    list(FIND kCoreOrder ${folder} rank)
    if(rank LESS 0)
      list(APPEND problems "core/${folder}: a folder kCoreOrder in tests/layers/CheckLayers.cmake does not place")
      continue()
    endif()
    file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/core/${folder}/*.h"
         "${SOURCE_DIR}/core/${folder}/*.cpp")
    foreach(source ${sources})
      file(STRINGS "${SOURCE_DIR}/${source}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"core/")
      foreach(line ${includes})
        string(REGEX REPLACE "^[^\"]*\"core/([^/]+)/.*" "\\1" target "${line}")
        list(FIND kCoreOrder ${target} target_rank)
        if(target_rank GREATER rank)
          string(STRIP "${line}" line)
          list(APPEND problems "${source}: ${line} (core/${folder}/ comes before core/${target}/ and must not include it)")
        endif()
      endforeach()
    endforeach()
  endif()
endforeach()

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
