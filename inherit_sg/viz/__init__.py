"""Visual logging of maps and queries to external viewers (Rerun). Nothing here is
imported unless a command asks for it."""
