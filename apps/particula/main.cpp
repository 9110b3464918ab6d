// particula command-line program (placeholder until the CLI lands in this commit series).
#include <cstdio>
int main() { std::puts("particula"); return 0; }
