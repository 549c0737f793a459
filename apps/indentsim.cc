// indentsim command-line entry point (placeholder; the real app is assembled in src/).
int main() { return 0; }
