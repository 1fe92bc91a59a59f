// Empty: the target that compiles a precompiled header for the others to reuse.
