// A build without MPI under an MPI launcher refuses, in one line from the first process alone,
// rather than render the whole image in every process (issue 70).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "app/mpi_launch.h"

namespace {

rtiow::EnvironmentLookup environment(const std::map<std::string, std::string>& values) {
  return [values](const char* name) -> const char* {
    const auto found = values.find(name);
    return found == values.end() ? nullptr : found->second.c_str();
  };
}

TEST(MpiLaunch, ABuildWithoutMpiRefusesSeveralProcesses) {
  const auto open_mpi = environment({{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_RANK", "1"}});
  const std::string why = rtiow::launch_refusal(false, open_mpi);
  EXPECT_NE(why.find("one of 2 processes"), std::string::npos) << why;
  EXPECT_NE(why.find("built without MPI"), std::string::npos) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos) << "one line";
  EXPECT_FALSE(rtiow::first_of_launch(open_mpi)) << "rank 1 stays silent";
  EXPECT_TRUE(rtiow::first_of_launch(environment({{"PMI_RANK", "0"}})));

  EXPECT_NE(rtiow::launch_refusal(false, environment({{"PMI_SIZE", "4"}})).find("one of 4"),
            std::string::npos);
}

TEST(MpiLaunch, OneProcessOrABuildWithMpiGoesOn) {
  EXPECT_EQ(rtiow::launch_refusal(false, environment({})), "") << "no launcher";
  EXPECT_EQ(rtiow::launch_refusal(false, environment({{"OMPI_COMM_WORLD_SIZE", "1"}})), "")
      << "mpirun -np 1 renders the image once";
  EXPECT_EQ(rtiow::launch_refusal(false, environment({{"PMI_SIZE", "many"}})), "") << "not a count";
  EXPECT_EQ(rtiow::launch_refusal(true, environment({{"OMPI_COMM_WORLD_SIZE", "2"}})), "")
      << "a build with MPI shares the samples";
  EXPECT_TRUE(rtiow::first_of_launch(environment({}))) << "alone, it speaks";
}

}  // namespace
