# A full disk during a `geohybrid dem` run (issue 24). The snapshot file outgrows a file-size limit
# (bash's ulimit -S -f, with SIGXFSZ ignored): its write fails with EFBIG as it would with ENOSPC
# on a full disk, through the same write(2), without root or a mount. (A soft limit: the file
# abandoned after the failure is closed in memory, beyond the limit, which geohybrid lifts to
# the hard one for that close; dem/io/hdf5_writable_file.h.) HDF5 1.10 crashed inside
# MPI_Finalize after such a failure (rc 139). Expected: status 1, one error naming particles.h5
# and the failed write, no summary.json, and a .xdmf that lists only complete snapshots.
# cmake -DGEOHYBRID=... -DWORK=DIR -P check_full_disk.cmake
set(out ${WORK}/full_disk)
file(REMOVE_RECURSE ${out})
# 10,000 discs, a snapshot every 1e-4 s of 4e-3 s: some 40 snapshots of 0.8 MB, against a
# limit of 16 MB (MPI's start needs some 5 MB of shared memory files under the same limit).
file(WRITE ${WORK}/full_disk.prm "set output directory = ${out}
set threads = 1
subsection Particles
  set source = generate
  set shape = disc
  set number of particles = 10000
end
subsection Box
  set width = 1.0
  set height = 0.5
end
subsection Simulation
  set end time = 4e-3
  set output interval = 1e-4
  set snapshot interval = 1e-4
end
")
execute_process(COMMAND bash -c "trap '' XFSZ; ulimit -S -f 16384; exec \"$0\" dem \"$1\"" ${GEOHYBRID} ${WORK}/full_disk.prm
                OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr RESULT_VARIABLE status TIMEOUT 300)
string(REGEX MATCHALL "error:" errors "${stderr}")
list(LENGTH errors n)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "expected exit status 1 (an error, not a crash), got '${status}':\n${stdout}\n${stderr}")
endif()
if(NOT n EQUAL 1 OR NOT stderr MATCHES "DEM snapshot file '${out}/particles.h5'" OR NOT stderr MATCHES "File too large")
  message(FATAL_ERROR "expected one error naming ${out}/particles.h5 and the failed write, got ${n}:\n${stderr}")
endif()
if(EXISTS ${out}/summary.json)
  message(FATAL_ERROR "a summary.json was written for a run that failed")
endif()
file(READ ${out}/particles.xdmf xdmf)
string(REGEX MATCHALL "<Grid Name=\"particles\"" listed "${xdmf}")
list(LENGTH listed n_listed)
file(SIZE ${out}/particles.h5 size)
if(n_listed EQUAL 0 OR n_listed GREATER 30)
  message(FATAL_ERROR "the .xdmf lists ${n_listed} snapshots; expected the 20 or so that fit in 16 MB of the 41")
endif()
message(STATUS "status ${status}, ${n_listed} snapshots listed, particles.h5 ${size} bytes:\n${stderr}")
