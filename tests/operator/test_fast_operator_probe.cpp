// Probes of a fast setting (FastOptions::probe_samples): an operator that covers only the rows its
// self-check samples measures, bit for bit, what the whole operator's self-check measures (each
// row's covering (42), near field (43) and far coefficients (44)-(45) are computed independently of
// the other rows), and one exact reference serves every eta and M on the same rows.
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include "occluded_scenes.hpp"
#include "test_scenes.hpp"

#include "self_check_expectations.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace panelrad {
namespace {

Scene occluded_scene() {
  Scene scene = testing::general_scene(testing::room_with_box());
  std::vector<double> rho;
  for (Index f = 0; f < scene.num_facets(); ++f) rho.push_back(0.2 + 0.1 * static_cast<double>(f % 6));
  scene.set_reflectivity(rho);
  return scene;
}

FastOptions options(double eta, int degree, std::shared_ptr<const geometry::Occluders> occluders) {
  FastOptions o;
  o.eta = eta;
  o.degree = degree;
  o.occluders = std::move(occluders);
  return o;
}

using testing::expect_same_check;

void expect_probe_matches_whole(const Collocation& col, FastOptions o, int samples) {
  const FastOperator whole(col, o);
  o.probe_samples = samples;
  const FastOperator probe(col, o);
  const FastSelfCheck w = whole.self_check(samples), p = probe.self_check(samples);
  expect_same_check(w, p);
  ASSERT_FALSE(w.sampled_rows.empty());
  // The sampled rows are computed alike; the others are held empty.
  for (Index i = 0; i < col.size(); ++i) {
    const bool sampled = std::binary_search(w.sampled_rows.begin(), w.sampled_rows.end(), i);
    if (sampled) {
      EXPECT_EQ(detail::far_clusters(probe, i), detail::far_clusters(whole, i)) << "row " << i;
      EXPECT_EQ(detail::near_elements(probe, i), detail::near_elements(whole, i)) << "row " << i;
    } else {
      EXPECT_TRUE(detail::far_clusters(probe, i).empty() && detail::near_elements(probe, i).empty()) << "row " << i;
    }
  }
  EXPECT_GT(probe.statistics().far_pairs, 0u);
  EXPECT_LT(probe.statistics().far_pairs, whole.statistics().far_pairs);
}

TEST(FastOperatorProbe, OccludedProbeMeasuresTheWholeOperatorsCheck) {
  // Level 3: at level 2 the sampled rows' admissible clusters are all elements or clusters of
  // four, taken as near entries.
  const Scene scene = occluded_scene();
  const Collocation col(scene, 3);
  expect_probe_matches_whole(col, options(0.4, 4, scene_occluders(col.tree())), 16);
  expect_probe_matches_whole(col, options(0.3, 6, scene_occluders(col.tree())), 32);
}

TEST(FastOperatorProbe, ConvexProbeMeasuresTheWholeOperatorsCheck) {
  const Scene cube = testing::reflecting_builtin("cube");
  const Collocation col(cube, 3);
  expect_probe_matches_whole(col, options(0.5, 3, nullptr), 32);
}

// The exact side depends on the rows and the occluders only: a reference made by one operator
// gives every other setting on the same rows its own self_check exactly.
TEST(FastOperatorProbe, OneReferenceForEverySetting) {
  const Scene scene = occluded_scene();
  const Collocation col(scene, 2);
  const auto occluders = scene_occluders(col.tree());
  const FastOperator first(col, options(0.5, 2, occluders));
  const FastSelfCheckReference reference = first.self_check_reference(24);
  for (const auto& [eta, degree] : std::vector<std::pair<double, int>>{{0.5, 2}, {0.3, 5}, {0.2, 8}}) {
    const FastOperator op(col, options(eta, degree, occluders));
    expect_same_check(op.self_check(reference), op.self_check(24));
  }
  FastSelfCheckReference bad = reference;
  bad.rows.push_back(col.size());  // not a row
  EXPECT_THROW(first.self_check(bad), std::invalid_argument);
  bad = reference;
  bad.exact.pop_back();
  EXPECT_THROW(first.self_check(bad), std::invalid_argument);
}

TEST(StricterSettings, SmallerEtaOrLargerDegreeOnly) {
  OperatorOptions o;
  o.method = OperatorMethod::fast;
  o.eta = 0.4;
  o.degree = 8;
  const std::vector<OperatorOptions> s = stricter_settings(o);
  ASSERT_EQ(s.size(), 12u);  // (0.4: M 9, 10), (0.3 and 0.2: M 6..10)
  for (const OperatorOptions& x : s) {
    EXPECT_TRUE(x.eta < o.eta || (x.eta == o.eta && x.degree > o.degree)) << describe_parameters(x);
    EXPECT_GE(x.eta, 0.2);
    EXPECT_GE(x.degree, 6);
    EXPECT_LE(x.degree, 10);
  }
  o.eta = 0.1;
  o.degree = 12;
  EXPECT_TRUE(stricter_settings(o).empty());
  o.degree = 1;
  EXPECT_EQ(stricter_settings(o).size(), 2u);  // M 2, 3
  o.method = OperatorMethod::dense;
  EXPECT_TRUE(stricter_settings(o).empty());
}

}  // namespace
}  // namespace panelrad
