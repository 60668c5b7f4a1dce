# cmake -DSUMMARY=summary.json -DOUT=file -P summary_rms.cmake: writes the RMS
# of every output in a summary.json of `deb run` as "RMS<tab>NAME" lines, in
# the order of the outputs (what tests/consumer/main.cpp prints).
file(READ "${SUMMARY}" json)
string(JSON count LENGTH "${json}" outputs)
set(lines "")
if(count GREATER 0)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON name GET "${json}" outputs ${i} name)
    string(JSON rms GET "${json}" outputs ${i} rms)
    string(APPEND lines "${rms}\t${name}\n")
  endforeach()
endif()
file(WRITE "${OUT}" "${lines}")
