#pragma once
// How full a horizontal slab of a tank is: the share of each grain that lies in it, each disc cut
// exactly at the slab's levels, and the area the laid sheets take in it. A lift's growth stops on
// its slab's porosity and the filled tank reports it (tank_filling.h).
//
// Porosities are of the space the grains can fill: the area of a sheet in a slab (its thickness
// times its length there) is not counted as void.
#include "dem/particles.h"
#include "dem/spar_sheet.h"

#include <cstddef>
#include <vector>

namespace geohybrid::dem
{
/// Porosity of the horizontal slab y in [y_bottom, y_top], x in [x_min, x_max]: one minus the
/// solid area inside it over its area, each disc cut exactly at the slab's top and bottom (discs
/// are taken to lie within [x_min, x_max], as between a tank's side walls). The discs of a
/// cluster count in proportion to their areas, scaled to the cluster's area (so the lens where
/// they overlap is not counted twice).
double slab_porosity(const ParticleSet &particles, double x_min, double x_max, double y_bottom, double y_top);

/// Share of body b's solid area that lies in the slab y in [y0, y1]: each disc cut exactly, the
/// discs of a cluster weighted by their areas (which leaves out the lens where they overlap).
double share_in_slab(const ParticleSet &p, std::size_t b, double y0, double y1);

/// Area the sheets take in the slab y in [y0, y1], x in [x_min, x_max] (a tank's: [0, width]):
/// each segment a band of the sheet's thickness, cut at the slab's levels piece by piece.
double sheet_area_in_slab(const std::vector<SparSheet> &sheets, double x_min, double x_max, double y0, double y1);

/// slab_porosity over x in [0, width] of the space the grains can fill: without the area the
/// sheets take in the slab.
double slab_porosity_beside_sheets(const ParticleSet &particles, const std::vector<SparSheet> &sheets, double width,
                                   double y_bottom, double y_top);
} // namespace geohybrid::dem
