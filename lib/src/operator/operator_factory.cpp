#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>

#include <stdexcept>

namespace panelrad {

const char* to_string(OperatorMethod method) {
  switch (method) {
    case OperatorMethod::automatic: return "auto";
    case OperatorMethod::dense: return "dense";
    case OperatorMethod::fast: return "fast";
  }
  return "?";
}

OperatorMethod parse_operator_method(const std::string& name) {
  if (name == "auto") return OperatorMethod::automatic;
  if (name == "dense") return OperatorMethod::dense;
  if (name == "fast") return OperatorMethod::fast;
  throw std::invalid_argument("operator method '" + name + "' is not auto, dense or fast");
}

const char* to_string(Visibility visibility) {
  switch (visibility) {
    case Visibility::automatic: return "auto";
    case Visibility::unoccluded: return "unoccluded";
    case Visibility::occluded: return "occluded";
  }
  return "?";
}

Visibility parse_visibility(const std::string& name) {
  if (name == "auto") return Visibility::automatic;
  if (name == "unoccluded") return Visibility::unoccluded;
  if (name == "occluded") return Visibility::occluded;
  throw std::invalid_argument("visibility '" + name + "' is not auto, unoccluded or occluded");
}

std::string visibility_problem(Visibility visibility, geometry::SceneShape shape) {
  if (visibility == Visibility::automatic)
    return "visibility 'auto' is not an operator's: unoccluded or occluded (the solver resolves auto from the "
           "scene's shape)";
  if (visibility == Visibility::unoccluded && shape != geometry::SceneShape::convex)
    return "visibility unoccluded (V = 1 for every pair of points) is the paper's assumption of a convex surface, "
           "exact only there, and this scene is not proven convex (" + std::string(geometry::to_string(shape)) +
           "): its faces hide parts of it from others, which V = 1 would count as seen (entries of K_n < 0 where a "
           "face is seen from its back); use occluded: V computed, as the solver's auto does on such a scene";
  return "";
}

VisibilityWork visibility_work(const RadiosityOperator& op) {
  VisibilityWork w;
  if (const auto* fast = dynamic_cast<const FastOperator*>(&op)) {
    const FastStatistics& s = fast->statistics();
    w.computed = s.occluded;
    w.visible_pairs = s.visible_pairs;
    w.hidden_pairs = s.hidden_pairs;
    w.partial_pairs = s.partial_pairs;
    w.clipped_elements = s.clipped_elements;
    w.rays_cast = s.rays_cast;
  } else if (const auto* dense = dynamic_cast<const DenseOperator*>(&op)) {
    w.computed = dense->occluded();
    w.visible_pairs = dense->visible_pairs();
    w.hidden_pairs = dense->hidden_pairs();
    w.partial_pairs = dense->partial_pairs();
    w.clipped_elements = dense->clipped_elements();
  }
  return w;
}

std::shared_ptr<const geometry::Occluders> scene_occluders(const geometry::ClusterTree& tree) {
  geometry::TriangleMesh faces;
  faces.source = "scene faces";
  const auto roots = tree.level(0);
  faces.vertices.reserve(3 * roots.size());
  for (const geometry::Cluster& c : roots) {
    const auto first = static_cast<geometry::Index>(faces.vertices.size());
    for (const Vec3& v : c.vertex) faces.vertices.push_back(v);
    faces.triangles.push_back({first, first + 1, first + 2});
    faces.facet_of_triangle.push_back(c.facet);
  }
  faces.num_facets = tree.num_facets();
  return std::make_shared<const geometry::Occluders>(faces);
}

bool single_precision_far_field(Visibility) { return true; }

bool single_precision_near_field(Visibility visibility) { return visibility == Visibility::occluded; }

std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options,
                                                 Visibility visibility, const SetupProgress& progress,
                                                 const RowRange& rows, int probe_samples) {
  // unoccluded: V = 1, exact on a convex surface only (operator_factory.hpp); both operators
  // integrate G without a visibility factor and do no visibility work. occluded: V from the
  // scene's faces.
  if (const std::string why = visibility_problem(visibility, collocation.shape()); !why.empty())
    throw std::invalid_argument("make_operator: " + why);
  const std::shared_ptr<const geometry::Occluders> occluders =
      visibility == Visibility::occluded ? scene_occluders(collocation.tree()) : nullptr;
  switch (options.method) {
    case OperatorMethod::dense:
      if (progress)
        progress("dense matrix, n = " + std::to_string(collocation.size()) +
                 (occluders ? ", with visibility" : ""));
      return std::make_unique<DenseOperator>(collocation, options.near, occluders);
    case OperatorMethod::fast: {
      FastOptions fast;
      static_cast<ClusteringParameters&>(fast) = options;
      fast.near = options.near;
      fast.progress = progress;
      fast.occluders = occluders;
      fast.single_precision_coefficients = single_precision_far_field(visibility);
      fast.single_precision_near = single_precision_near_field(visibility);
      fast.expected_products = options.expected_products;
      fast.rows = rows;
      fast.probe_samples = probe_samples;
      return std::make_unique<FastOperator>(collocation, fast);
    }
    case OperatorMethod::automatic: break;
  }
  throw std::invalid_argument(std::string("make_operator: method '") + to_string(options.method) +
                              "' is not an operator: dense or fast (choose_parameters resolves auto)");
}

}  // namespace panelrad
