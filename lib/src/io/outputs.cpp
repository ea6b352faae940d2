#include <panelrad/io/outputs.hpp>

#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

#include <algorithm>
#include <stdexcept>

namespace panelrad {

std::vector<std::string> output_paths(const std::string& prefix, const std::vector<std::string>& formats) {
  if (formats.empty()) throw std::invalid_argument("outputs: no format given (csv, ply, vtk, png)");
  const std::vector<std::string>& known = output_formats();
  for (std::size_t i = 0; i < formats.size(); ++i) {
    if (std::find(known.begin(), known.end(), formats[i]) == known.end())
      throw std::invalid_argument("outputs: '" + formats[i] + "' is not csv, ply, vtk or png");
    if (std::find(formats.begin(), formats.begin() + static_cast<std::ptrdiff_t>(i), formats[i]) !=
        formats.begin() + static_cast<std::ptrdiff_t>(i))
      throw std::invalid_argument("outputs: '" + formats[i] + "' is given twice");
  }
  std::vector<std::string> paths;
  for (const std::string& f : known)
    if (std::find(formats.begin(), formats.end(), f) != formats.end()) paths.push_back(prefix + "." + f);
  return paths;
}

std::vector<std::string> write_outputs(const SceneSolution& solution, const std::string& prefix,
                                       const std::vector<std::string>& formats, const OutputOptions& options) {
  const std::vector<std::string> paths = output_paths(prefix, formats);
  check_channel_names(solution.field.channels);
  OutputSet set;
  for (const std::string& path : paths) {
    const std::string format = path.substr(path.size() - 3);
    if (format == "csv") set.add(path, radiosity_csv(solution.field));
    if (format == "ply") set.add(path, radiosity_ply(solution.field));
    if (format == "vtk") set.add(path, radiosity_vtk(solution.field));
    if (format == "png") {
      RenderOptions view;  // what is not given is chosen from the scene
      view.view_from_scene = !options.view_direction;
      if (options.view_direction) view.view_direction = *options.view_direction;
      view.up_from_scene = !options.up;
      if (options.up) view.up = *options.up;
      set.add(path, radiosity_png(solution.field, view));
    }
  }
  set.commit();
  return paths;
}

}  // namespace panelrad
