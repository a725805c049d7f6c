// SPDX-License-Identifier: MIT
// The installed package's consumer: exits 0 when the game's checks pass.
int play();
int main() {
  return play();
}
