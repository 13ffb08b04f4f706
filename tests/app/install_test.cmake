# Installed and moved copies of godfinger find their bundled data beside themselves:
#   cmake -DBINARY_DIR=<build> -DWORK=<scratch folder> -DPYTHON3=<python3> -P install_test.cmake
# 1. `cmake --install` into a temporary prefix; a scene added to the installed data only is
#    listed, and a bundled scene with a mesh (concave-mesh: the bunny) runs from another folder.
#    The device protocol and the example device program are installed where the installed
#    device-udp scene says, and the program finds its default scene (the Fig. 8 pinch) there.
# 2. The executable and its share/ folder copied elsewhere (a moved build tree): the same.
# GODFINGER_DATA and GODFINGER_SCENES are cleared, so only the executable's place can tell.
unset(ENV{GODFINGER_DATA})
unset(ENV{GODFINGER_SCENES})
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

function(check_copy label exe data)
  file(COPY_FILE "${data}/scenes/fig5-push-ball.toml" "${data}/scenes/only-in-${label}.toml")
  execute_process(COMMAND "${exe}" list WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE listed RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${label}: godfinger list failed (${failed})")
  endif()
  foreach(scene only-in-${label} fig8-pinch-oscillation concave-mesh)
    string(FIND "${listed}" "${scene} " at)
    if(at LESS 0)
      message(FATAL_ERROR "${label}: godfinger list does not show ${scene}:\n${listed}")
    endif()
  endforeach()
  string(FIND "${listed}" "does not load" broken)
  if(NOT broken LESS 0)
    message(FATAL_ERROR "${label}: a bundled scene does not load:\n${listed}")
  endif()
  execute_process(COMMAND "${exe}" run concave-mesh --quiet --duration 0.02 --out "${WORK}/run-${label}"
                  WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE failed ERROR_VARIABLE said)
  if(failed OR NOT EXISTS "${WORK}/run-${label}/summary.json")
    message(FATAL_ERROR "${label}: concave-mesh did not run (${failed}):\n${said}")
  endif()
endfunction()

execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${WORK}/prefix"
                OUTPUT_QUIET RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "cmake --install failed (${failed})")
endif()
check_copy(installed "${WORK}/prefix/bin/godfinger" "${WORK}/prefix/share/godfinger")

set(doc "${WORK}/prefix/share/doc/godfinger")
file(READ "${WORK}/prefix/share/godfinger/scenes/device-udp.toml" scene)
foreach(file device-protocol.md examples/device-udp/client.py)
  if(NOT EXISTS "${doc}/${file}")
    message(FATAL_ERROR "cmake --install did not install ${doc}/${file}")
  endif()
  string(FIND "${scene}" "share/doc/godfinger/${file}" named)
  if(named LESS 0)
    message(FATAL_ERROR "the installed device-udp scene does not say where ${file} is installed")
  endif()
endforeach()
# The client run for no time: one packet per finger to loopback's discard port, where nothing
# answers (so it exits 1); its JSON line counts the fingers of the scene it found.
execute_process(COMMAND "${PYTHON3}" "${doc}/examples/device-udp/client.py" --port 9 --seconds 0 --rate 1
                WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE said ERROR_VARIABLE complained)
string(FIND "${said}" "\"channels\": 2" found)
if(found LESS 0)
  message(FATAL_ERROR "the installed client.py did not load its default scene:\n${said}${complained}")
endif()

file(MAKE_DIRECTORY "${WORK}/moved")
file(COPY "${BINARY_DIR}/godfinger" DESTINATION "${WORK}/moved")
file(COPY "${BINARY_DIR}/share" DESTINATION "${WORK}/moved")
check_copy(moved "${WORK}/moved/godfinger" "${WORK}/moved/share/godfinger")

# 3. The Python module (when built): installed under the prefix's PYTHON_MODULE_DIR, imported
#    from another folder through PYTHONPATH, it runs a scene found only in the installed data.
if(PYTHON_MODULE_DIR)
  set(modules "${WORK}/prefix/${PYTHON_MODULE_DIR}")
  file(GLOB installed "${modules}/godfinger.*.so")
  if(NOT installed)
    message(FATAL_ERROR "cmake --install did not put the Python module into ${modules}")
  endif()
  set(ENV{PYTHONPATH} "${modules}")
  execute_process(COMMAND "${PYTHON3}" -c [[
import godfinger
run = godfinger.run("only-in-installed", duration=0.01)
print(godfinger.__file__, len(run.trace["t"]))
]] WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE said ERROR_VARIABLE complained RESULT_VARIABLE failed)
  if(failed OR NOT said MATCHES "^${modules}/godfinger[^ ]*\\.so 10\n$")
    message(FATAL_ERROR "the installed Python module did not run a scene of the installed data (${failed}):\n${said}${complained}")
  endif()
endif()
