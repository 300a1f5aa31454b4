#pragma once
// The coupled patch of the coupling tests: the library's (coupling/benchmark_patch.h, shared with
// `geohybrid coupling-test`), a hexagonal lattice of bonded equal discs and a Q1 mesh of the
// matching plane-strain continuum overlapping in a band four particle spacings and two cells wide.
#include "coupling/benchmark_patch.h"
#include "coupling/coupling_benchmarks.h"
#include "coupling/hexagonal_lattice.h"
#include "test_coupling_support.h"
