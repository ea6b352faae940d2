#pragma once
// The work of rows of the fast operator with the line of sight V(P, Q), measured on sampled rows:
// their coverings (42) walked with the scene's occluders (visible_covering.hpp), counting what
// setup and products do per row. For cutting the rows between processes where visibility makes
// the rows' costs uneven (a row in a corner of a room classifies many more pairs than one in the
// open). Without V, FastOperator::estimate_memory counts the pairs of the plain coverings.
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/near_field.hpp>

namespace panelrad {

/// Per row on average over up to `samples` evenly spaced rows of `rows` (rows with rho = 0 count
/// 0): far pairs x Taylor terms + near pairs (a product's work, (43)-(48)) + the (P, cluster)
/// pairs classified by the occluders x Taylor terms (the setup's shaft classifications, each
/// counted as one pair's far-field coefficients). Deterministic.
double occluded_row_work(const Collocation& collocation, const geometry::Occluders& occluders, double eta, int degree,
                         const NearFieldOptions& near, const RowRange& rows, int samples);

}  // namespace panelrad
