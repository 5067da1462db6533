// Placeholder so the component links before its first source lands; delete when adding real sources.
namespace pgmcl::detail { int sims_placeholder() { return 0; } }
