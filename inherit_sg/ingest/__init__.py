"""Frame sources: the isg dataset folder, a synthetic world with renderer and query
generator, and readers for real dataset layouts. Every reader yields
:class:`inherit_sg.model.Frame` in the z-up world frame."""
