import panelrad

scene = panelrad.load_scene("examples/scenes/cornell_box.obj")
solution = panelrad.solve_scene(scene, level=3)  # n = 4^3 n0 elements, every channel
solution.require_converged()
u = solution["R"].radiosity  # a numpy array: u at the element centroids (red channel)
print(f"n = {solution.n}, u from {u.min():.4g} to {u.max():.4g}")
