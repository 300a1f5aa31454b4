#pragma once
// The coupled patch of the coupling tests: the library's (apps/coupling_benchmarks/coupled_patch.h, shared with
// `geohybrid coupling-test`), a hexagonal lattice of bonded equal discs and a Q1 mesh of the
// matching plane-strain continuum overlapping in a band four particle spacings and two cells wide.
#include "apps/coupling_benchmarks/coupled_patch.h"
#include "apps/coupling_benchmarks/coupling_benchmarks.h"
#include "apps/coupling_benchmarks/hexagonal_lattice.h"
#include "test_coupling_support.h"
