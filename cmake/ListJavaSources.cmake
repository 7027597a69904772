# cmake -DSRC=dir -DOUT=file -P ListJavaSources.cmake: write the .java files under SRC, one per line, for javac @file.
file(GLOB_RECURSE java_sources ${SRC}/*.java)
string(REPLACE ";" "\n" text "${java_sources}")
file(WRITE ${OUT} "${text}\n")
