// Included by errors/included_error.comp; the error is on line 4 of this file.
float brokenHelper(float x) {
  float y = x;
  return y + missingVariable;
}
