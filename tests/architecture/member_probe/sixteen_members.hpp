// A class with 16 data members: architecture.member_count_check_rejects_sixteen expects
// tests/architecture/member_count_check.cmake to refuse it.
#pragma once

class SixteenMembers {
 public:
  int sum() const;

 private:
  int m0_ = 0;
  int m1_ = 1;
  int m2_ = 2;
  int m3_ = 3;
  int m4_ = 4;
  int m5_ = 5;
  int m6_ = 6;
  int m7_ = 7;
  int m8_ = 8;
  int m9_ = 9;
  int m10_ = 10;
  int m11_ = 11;
  int m12_ = 12;
  int m13_ = 13;
  int m14_ = 14;
  int m15_ = 15;
};
