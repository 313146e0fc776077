"""The semantic stream's mapping logic: observations from keyframes, association and
fusion into object nodes, areas, relations, summaries, events and orchestration."""
