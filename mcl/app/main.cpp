#include <cstdio>
int main() { std::puts("pgmcl: under construction"); return 0; }
