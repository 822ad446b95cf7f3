// Placeholder until the assignment solver lands.
