// SPDX-License-Identifier: MIT
// The vendoring game's entry point: exits 0 when the game's checks pass.
int play();
int main() {
  return play();
}
