namespace particula { int placeholder_symbol = 0; }
