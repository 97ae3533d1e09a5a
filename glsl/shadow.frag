// Shadow maps store depth only.
void main() {}
